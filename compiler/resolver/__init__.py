"""The front end's second half: the loaded, structurally valid document becomes the
immutable Protocol model, and every semantic rule of the language is checked here,
each error at its file:line:col. One module per concern, each a mixin of the
Resolver: types (enums, flags, groups), fields, checksums, framing (envelopes,
placement, sizes), messages (dispatch, examples), rules, sequences, delivery (the
machine pair the lossy-link simulator drives); machines.py resolves the state
machines, text.py schema prose, base.py what they share."""
from __future__ import annotations

from .protocol import Resolver, resolve

__all__ = ["Resolver", "resolve"]
