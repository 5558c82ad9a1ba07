"""What the compiled accelerator of a protocol's Python module does: for each message
it can serve, a C function that decodes a frame with the generated C decoder and
builds the same object the Python decoder builds, value for value (and, in
encode.py, one that encodes it).

A frame the C decoder refuses goes to the Python decoder, so errors are Python's own.
A message with a value the accelerator cannot build exactly as Python does (text,
optional binary values, one-hot fields: scope.py) is left to Python."""
from __future__ import annotations

from typing import Optional

from ...model import Field, Message, Protocol, count_member
from ..c.view import CView
from ..code import Code
from ..python.view import PythonView, lit
from .encode import EncoderView
from .names import Names
from .presence import sent_test
from .scope import servable


class AcceleratorView:
    def __init__(self, p: Protocol):
        self.p = p
        self.c = CView(p)
        self.py = PythonView(p)
        self.names = Names()
        self.count = 0  # locals made so far: each name is used once

    def messages(self) -> list[Message]:
        return [m for m in self.p.messages if servable(self.p, m)]

    def functions(self) -> list[dict]:
        out = []
        for m in self.messages():
            body = Code()
            body.indent()
            self.build(body, m, m.layout, (), "o", self.py.class_name(m), "m->")
            out.append({"name": m.name, "cls": self.names.class_global(self.py.class_name(m)),
                        "pure": self.names.g(f"_decode_{m.name}"), "decode": self.c.fn(m, "decode"),
                        "ctype": self.c.tname(m), "kind": self.c.upper("MSG", m.name), "body": body.text()})
        return out

    def encoders(self) -> list[dict]:
        return EncoderView(self.p, self.names, self.c, self.py).functions()

    def build(self, c: Code, m: Message, fields: tuple[Field, ...], path: tuple, var: str, cls: str,
              member: str) -> None:
        """Code that fills the object in `var` (of class `cls`, held by the message object)
        from the C struct members named `member` + field name. Each object made is given
        to its owner at once, so `goto fail` has only the message object to release."""
        for f in fields:
            if f.is_member:
                self.assign(c, m, f, path + (f.name,), var, cls, member + f.name)

    def assign(self, c: Code, m: Message, f: Field, path: tuple, owner: str, cls: str, at: str) -> None:
        slot = self.names.s(cls, f.name)
        sent = sent_test(self.c, m, f, "m->")
        if sent is None:
            self.assign_value(c, m, f, path, owner, slot, at)
            return
        c(f"if ({sent}) {{")  # else None, as Python gives a value the frame leaves out
        c.indent()
        self.assign_value(c, m, f, path, owner, slot, at)
        c.dedent()
        c("} else {")
        c(f"    if (acc_set(st, {owner}, {slot}, acc_none()) < 0) goto fail;")
        c("}")

    def assign_value(self, c: Code, m: Message, f: Field, path: tuple, owner: str, slot: str, at: str) -> None:
        if f.count is None:
            if f.kind == "group":
                group, group_cls = self.local("g"), self.py.group_class(m, path)
                c(f"PyObject *{group} = acc_new({self.names.class_global(group_cls)});")
                c(f"if (acc_set(st, {owner}, {slot}, {group}) < 0) goto fail;")
                self.build(c, m, f.fields, path, group, group_cls, at + ".")
            else:
                c(f"if (acc_set(st, {owner}, {slot}, {self.value(f, at, self.in_use(f))}) < 0) goto fail;")
            return
        items, i = self.local("l"), self.local("i")
        count = self.in_use(f) or str(f.count)
        c(f"PyObject *{items} = PyList_New({count});")
        c(f"if (acc_set(st, {owner}, {slot}, {items}) < 0) goto fail;")
        c(f"for (Py_ssize_t {i} = 0; {i} < {count}; {i}++) {{")
        c.indent()
        element = path + (0,)
        item = self.local("g" if f.kind == "group" else "v")
        if f.kind == "group":
            c(f"PyObject *{item} = acc_new({self.names.class_global(self.py.group_class(m, element))});")
        else:
            c(f"PyObject *{item} = {self.value(f, f'{at}[{i}]')};")
        c(f"if ({item} == NULL) goto fail;")
        c(f"PyList_SET_ITEM({items}, {i}, {item});")
        if f.kind == "group":
            self.build(c, m, f.fields, element, item, self.py.group_class(m, element), f"{at}[{i}].")
        c.dedent()
        c("}")

    @staticmethod
    def in_use(f: Field) -> Optional[str]:
        """How many elements (or bytes) of a field that varies the frame carried: its
        count member (a top-level field's, the only ones served)."""
        return f"(Py_ssize_t)m->{count_member(f.name)}" if f.varies else None

    def local(self, prefix: str) -> str:
        self.count += 1
        return f"{prefix}{self.count}"

    def value(self, f: Field, at: str, length: Optional[str] = None) -> str:
        """A C expression giving a leaf's Python value: a new reference, NULL on error
        (`length`: the bytes in use of a bytes field that varies)."""
        f = f.element
        if f.kind == "bool":
            return f"PyBool_FromLong({at})"
        if f.kind == "float":
            return f"PyFloat_FromDouble((double){at})"
        if f.kind == "bytes":
            return f"PyBytes_FromStringAndSize((const char *){at}, {length or f.length})"
        number = self.int_value(f, at)
        if f.enum is not None and f.enum.open:  # a value no member has stays a number
            return f"acc_member_or_number({self.names.dict_global(f'_ENUM_{f.enum.name}')}, {number})"
        if f.enum is not None:
            return f"acc_lookup({self.names.g(f'_ENUM_{f.enum.name}')}, {number})"
        if f.flags is not None:
            if f.exactly_one or PythonView.all_flag_values(f.flags):
                return f"acc_lookup({self.names.g(f'_FLAGS_{f.flags.name}')}, {number})"
            table = self.names.dict_global(f"_FLAGS_{f.flags.name}")
            cls = self.names.g(PythonView.enum_class(f.flags.name))
            return f"acc_flags({table}, {cls}, {self.names.g('_flag')}, {number})"
        if f.scale is None:
            return number
        if isinstance(f.scale, float) and abs(f.offset or 0) < 2 ** 53 and f.bits <= 53:
            # the raw value is exact as a double, so C's product (and sum) round as Python's
            offset = f" + {float(f.offset)!r}" if f.offset else ""
            return f"PyFloat_FromDouble((double){at} * {f.scale!r}{offset})"
        offset = self.names.k(lit(f.offset)) if f.offset else "NULL"
        return f"acc_scaled({number}, {self.names.k(lit(f.scale))}, {offset})"

    def int_value(self, f: Field, at: str) -> str:
        if self.c.rep(f).ctype.startswith("u"):
            return f"PyLong_FromUnsignedLongLong((unsigned long long){at})"
        return f"PyLong_FromLongLong((long long){at})"

    def constants(self) -> list[tuple[str, bool]]:
        """Each constant as a C literal and whether it is a float."""
        return [(x, "." in x or "e" in x) for x in self.names.constants]
