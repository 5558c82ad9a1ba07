"""The front end's second half: the loaded, structurally valid document becomes the
immutable Protocol model, and every semantic rule of the language is checked here,
each error at its file:line:col. protocol.py resolves types, fields, framing,
messages, dispatch, rules and sequences; machines.py the delivery machines;
text.py schema prose."""
from __future__ import annotations

from .protocol import Resolver, resolve

__all__ = ["Resolver", "resolve"]
