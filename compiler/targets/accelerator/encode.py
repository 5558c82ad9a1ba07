"""The accelerator's encoders: for each message it can serve, a C function that reads
the message object into the generated C struct and writes the frame with the generated
C encoder.

C takes only what the Python encoder takes on its usual path, and converts it as
Python does: values of the exact classes Python reads without a conversion (an int, a
float, an enum member, True and False, bytes, a list), in range. Anything else (a
value of another class, out of range, a group object of a subclass, a value a frame
leaves out where it should be sent) goes to the Python encoder, which encodes or
refuses it as it always does: every error is the Python module's own."""
from __future__ import annotations

from fractions import Fraction
from typing import Optional

from ...model import Field, Leaf, Message, Protocol, count_member
from ..c.scalars import unsigned_type
from ..c.view import CView
from ..code import Code
from ..python.view import PythonView
from .names import Names
from .presence import sent_test
from .scope import servable


def encodable(p: Protocol, m: Message) -> bool:
    """Whether C reads every value of the message as the Python encoder does."""
    if not servable(p, m) or m.rules:  # a rule on logical values: C tests raw ones
        return False
    view = PythonView(p)
    return all(_leaf_encodable(view, m, leaf) for leaf in m.wire.leaves
               if _is_member_leaf(m, leaf))


def _is_member_leaf(m: Message, leaf: Leaf) -> bool:
    return all(f.is_member for f in _fields_on(m, leaf))


def _fields_on(m: Message, leaf: Leaf) -> list[Field]:
    """The fields a leaf's path passes through, the leaf's own last."""
    out, fields = [], m.layout
    for part in leaf.path:
        if isinstance(part, int):
            continue
        f = next(x for x in fields if x.name == part)
        out.append(f)
        fields = f.fields
    return out


def number_spec(view: PythonView, leaf: Leaf) -> Optional[tuple]:
    """The usual test of a number (PythonView.usual_spec); a float that may be NaN is served
    for its finite values, NaN and the infinities going to Python, which writes them."""
    spec = view.usual_spec(leaf)
    f = leaf.field
    if spec is None and f.kind == "float" and not f.finite:
        return ("float", leaf.path[-1], f.bits == 32)
    return spec


def _leaf_encodable(view: PythonView, m: Message, leaf: Leaf) -> bool:
    f = leaf.field
    if f.one_hot or f.optional:
        return False
    if f.kind == "bool" or f.kind == "bytes":
        return not f.values
    if f.enum is not None:
        return f.enum.kind != "char"
    if f.flags is not None:
        return True
    spec = number_spec(view, leaf)
    if spec is None:
        return False
    if spec[0] == "float":
        return not f.values
    _, _, lo, hi, scaled, *_ = spec
    if not scaled:
        return all(isinstance(x, int) and not isinstance(x, bool) for x in (lo, hi))
    numbers = (lo, hi, f.scale, f.offset or 0)
    return f.bits < 53 and not f.values and all(_exact_double(x) for x in numbers)


def _exact_double(x: object) -> bool:
    """A number that a C double literal holds exactly: Python compares and computes with it
    as C does."""
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        return False
    return abs(x) < 2 ** 53 if isinstance(x, int) else x == x and abs(x) != float("inf")


def _count_type(f: Field) -> str:
    """The C type of the member counting the elements (or bytes) in use of a field that varies."""
    return unsigned_type((f.length if f.kind == "bytes" else f.count).bit_length())


def c_double(x: float) -> str:
    """A C literal of exactly the double `x`."""
    return repr(float(x)) if Fraction(float(x)) == Fraction(x) else ""


SCRATCH = {"d": "double d;", "i": "long long i;", "u": "unsigned long long u;"}


class EncoderView:
    """The C code that reads a message object into its struct; `goto python` leaves
    anything else to the Python encoder."""

    def __init__(self, p: Protocol, names: Names, c: CView, py: PythonView):
        self.p, self.names, self.c, self.py = p, names, c, py
        self.count = 0
        self.scratch: set[str] = set()  # the function's scratch values in use: "i", "u", "d"

    def functions(self) -> list[dict]:
        out = []
        for m in self.p.messages:
            if not encodable(self.p, m):
                continue
            body = Code()
            body.indent()
            self.scratch = set()
            self.read(body, m, m.layout, (), "obj", self.py.class_name(m), "m.")
            out.append({"name": m.name, "cls": self.names.class_global(self.py.class_name(m)),
                        "pure": self.names.g(f"_encode_{m.name}"), "encode": self.c.fn(m, "encode"),
                        "ctype": self.c.tname(m), "size": self.c.upper(m.name, "SIZE"), "body": body.text(),
                        "scratch": [SCRATCH[x] for x in sorted(self.scratch)]})
        return out

    def local(self, prefix: str) -> str:
        self.count += 1
        return f"{prefix}{self.count}"

    def read(self, c: Code, m: Message, fields: tuple[Field, ...], path: tuple, obj: str, cls: str,
             member: str) -> None:
        """Code that fills the struct members named `member` + field name from the object in
        `obj` (of class `cls`)."""
        for f in fields:
            if not f.is_member:
                continue
            value = self.local("v")
            c(f"PyObject *{value} = acc_slot(st, {obj}, {self.names.s(cls, f.name)});")
            c(f"if ({value} == NULL) goto python;")
            sent = sent_test(self.c, m, f, member)
            if sent is not None:  # the value is there exactly when the frame sends it
                c(f"if (({sent}) != ({value} != Py_None)) goto python;")
                c(f"if ({value} != Py_None) {{")
                c.indent()
            self.read_field(c, m, f, path + (f.name,), value, member + f.name)
            if sent is not None:
                c.dedent()
                c("}")

    def read_field(self, c: Code, m: Message, f: Field, path: tuple, value: str, at: str) -> None:
        if f.count is None:
            if f.kind == "group":
                cls = self.py.group_class(m, path)
                c(f"if (Py_TYPE({value}) != (PyTypeObject *){self.names.class_global(cls)}) goto python;")
                self.read(c, m, f.fields, path, value, cls, at + ".")
            else:
                self.read_leaf(c, f, value, at, count_member(at) if f.varies else None)
            return
        n, i = self.local("n"), self.local("i")
        c(f"if (!PyList_CheckExact({value})) goto python;")
        c(f"Py_ssize_t {n} = PyList_GET_SIZE({value});")
        c(f"if ({n} {'>' if f.varies else '!='} {f.count}) goto python;")
        if f.varies:
            c(f"{count_member(at)} = ({_count_type(f)}){n};")
        c(f"for (Py_ssize_t {i} = 0; {i} < {n}; {i}++) {{")
        c.indent()
        item = self.local("e")
        c(f"PyObject *{item} = PyList_GET_ITEM({value}, {i});")
        element = path + (0,)
        if f.kind == "group":
            cls = self.py.group_class(m, element)
            c(f"if (Py_TYPE({item}) != (PyTypeObject *){self.names.class_global(cls)}) goto python;")
            self.read(c, m, f.fields, element, item, cls, f"{at}[{i}].")
        else:
            self.read_leaf(c, f.element, item, f"{at}[{i}]", None)
        c.dedent()
        c("}")

    def read_leaf(self, c: Code, f: Field, value: str, at: str, count: Optional[str]) -> None:
        """Code that checks one value as Python's usual path does and sets its member."""
        if f.kind == "bool":
            c(f"if ({value} != Py_True && {value} != Py_False) goto python;")
            c(f"{at} = {value} == Py_True;")
        elif f.kind == "bytes":
            length = self.local("k")
            c(f"if (!PyBytes_CheckExact({value})) goto python;")
            c(f"Py_ssize_t {length} = PyBytes_GET_SIZE({value});")
            c(f"if ({length} {'>' if count else '!='} {f.length}) goto python;")
            c(f"memcpy({at}, PyBytes_AS_STRING({value}), (size_t){length});")
            if count:
                c(f"{count} = ({_count_type(f)}){length};")
        elif f.enum is not None:  # a member, or an int of one: its raw value, as Python looks it up
            raw = self.local("r")
            cls = self.names.g(PythonView.enum_class(f.enum.name))
            table = self.names.dict_global(f"_RAW_{f.enum.name}")
            c(f"if (!PyLong_CheckExact({value}) && Py_TYPE({value}) != (PyTypeObject *){cls}) goto python;")
            c(f"PyObject *{raw} = PyDict_GetItemWithError({table}, {value});")
            self.scratch.add("i")
            c(f"if ({raw} == NULL || !acc_int({raw}, NULL, {self.c_ll(f.raw_range[0])}, {self.c_ll(f.raw_range[1])}, &i)) "
              "goto python;")
            self.allowed(c, f)
            c(f"{at} = ({self.c.rep(f).ctype})i;")
        elif f.flags is not None:  # an int or a flag of its class, of the set's bits only
            mask = f.flags.mask & ((1 << f.bits) - 1)
            cls = self.names.g(PythonView.enum_class(f.flags.name))
            self.scratch.add("i")
            c(f"if (!acc_int({value}, {cls}, 0, {mask}LL, &i) || (i & ~{mask}LL)) goto python;")
            if f.exactly_one:
                c("if (i == 0 || (i & (i - 1))) goto python;")
            c(f"{at} = ({self.c.rep(f).ctype})i;")
        else:
            self.read_number(c, f, value, at)

    def read_number(self, c: Code, f: Field, value: str, at: str) -> None:
        """A number Python checks by its usual test (PythonView.usual_spec) and converts."""
        ctype = self.c.rep(f).ctype
        spec = number_spec(self.py, Leaf(field=f, path=(f.name,), pos=None))
        if spec[0] == "float":
            self.scratch.add("d")
            limit = "3.4028234663852886e38" if spec[2] else "1.7976931348623157e308"
            c(f"if (!acc_float({value}, -{limit}, {limit}, &d)) goto python;")
            c(f"{at} = ({ctype})d;")
            return
        _, _, lo, hi, scaled, *_ = spec
        self.scratch.add("d" if scaled else "u" if hi > 2 ** 63 - 1 else "i")
        if scaled:  # Python's _floor((v - offset) / scale + 0.5), in doubles as Python's are
            offset = f" - {c_double(f.offset)}" if f.offset else ""
            raw_lo, raw_hi = f.raw_range
            c(f"if (!acc_float({value}, {c_double(lo)}, {c_double(hi)}, &d)) goto python;")
            c(f"d = floor((d{offset}) / {c_double(f.scale)} + 0.5);")
            c(f"if (!(d >= {float(raw_lo)!r} && d <= {float(raw_hi)!r})) goto python;")
            c(f"{at} = ({ctype})d;")
        elif hi > 2 ** 63 - 1:
            c(f"if (!acc_uint({value}, {lo}ULL, {hi}ULL, &u)) goto python;")
            c(f"{at} = ({ctype})u;")
        else:
            c(f"if (!acc_int({value}, NULL, {self.c_ll(lo)}, {self.c_ll(hi)}, &i)) goto python;")
            self.allowed(c, f)
            c(f"{at} = ({ctype})i;")

    def allowed(self, c: Code, f: Field) -> None:
        """The test of a field that takes only some values (`values:`), on its value in `i`."""
        if f.values:
            values = [PythonView.enum_value(f, x) if f.enum is not None else x for x in f.values]
            c(f"if ({' && '.join(f'i != {self.c_ll(v)}' for v in values)}) goto python;")

    @staticmethod
    def c_ll(x: int) -> str:
        """A long long literal of `x` (the most negative one has none of its own)."""
        return "(-9223372036854775807LL - 1)" if x == -2 ** 63 else f"{x}LL"
