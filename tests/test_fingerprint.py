"""The schema fingerprint: stable, blind to docs, sensitive to the wire, and
the same value in the model, the generated Python and the generated C."""
from __future__ import annotations

import re

from codeword.build import compile_schema
from codeword.fingerprint import fingerprint, fingerprint32
from conftest import DATA, PROTOCOLS, ROOT, SCHEMAS, load_generated


def _edited(tmp_path, name, old, new):
    text = (SCHEMAS / f"{name}.yaml").read_text(encoding="utf-8")
    assert text.count(old) == 1, old
    path = tmp_path / f"{name}.yaml"
    path.write_text(text.replace(old, new), encoding="utf-8")
    return compile_schema(path)


def test_generated_constants_match_the_model():
    for name in PROTOCOLS:
        p = compile_schema(SCHEMAS / f"{name}.yaml")
        fp = fingerprint(p)
        assert re.fullmatch(r"[0-9a-f]{16}", fp)
        module = load_generated(name)
        assert module.FINGERPRINT == fp
        assert module.FINGERPRINT32 == fingerprint32(p) == int(fp[:8], 16)
        header = (ROOT / "generated" / "c" / f"{name}.h").read_text(encoding="utf-8")
        assert f'#define {name.upper()}_FINGERPRINT "{fp}"' in header
        assert f"#define {name.upper()}_FINGERPRINT32 0x{fp[:8]}u" in header


def test_stable_across_loads_and_file_locations(tmp_path):
    a = compile_schema(SCHEMAS / "route.yaml")
    copy = tmp_path / "elsewhere.yaml"
    copy.write_text((SCHEMAS / "route.yaml").read_text(encoding="utf-8"), encoding="utf-8")
    assert fingerprint(a) == fingerprint(compile_schema(SCHEMAS / "route.yaml")) == fingerprint(compile_schema(copy))


def test_docs_examples_and_version_do_not_count(tmp_path):
    base = fingerprint(compile_schema(SCHEMAS / "car.yaml"))
    assert fingerprint(_edited(tmp_path, "car", "\nversion: \"0.3\"", "\nversion: \"0.3.1\"")) == base
    assert fingerprint(_edited(tmp_path, "car", "{en: \"1 if the car runs voice recognition.\"",
                               "{en: \"1 if the car listens.\"")) == base
    assert fingerprint(_edited(tmp_path, "car", "- name: master only, no slave program",
                               "- name: a master-only program")) == base


def test_wire_changes_count(tmp_path):
    base = fingerprint(compile_schema(SCHEMAS / "tank.yaml"))
    assert fingerprint(_edited(tmp_path, "tank", "range: [0, 100]", "range: [0, 99]")) != base
    assert fingerprint(compile_schema(DATA / "car_v0.2.yaml")) != fingerprint(compile_schema(SCHEMAS / "car.yaml"))


def test_checksum_final_steps_count_and_leave_older_schemas_alone(tmp_path):
    """complement and xorout change the fingerprint; a schema without them has no trace
    of them in the hashed model, so it keeps the fingerprint it had before they existed."""
    from codeword.fingerprint import canonical_json
    mtv4 = compile_schema(SCHEMAS / "mtv4.yaml")
    assert '"complement"' not in canonical_json(mtv4) and '"width":null' not in canonical_json(mtv4)
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    demo = re.search(r"`schemas/demo.yaml`:\n\n```yaml\n(.*?)```", readme, re.S).group(1)
    demo = re.sub(r"    examples:\n(.*\n)*", "", demo)  # each variant sends another checksum
    prints = set()
    for i, params in enumerate(["", "complement: twos, ", "complement: ones, ", "xorout: 0x5a, ",
                                "complement: ones, xorout: 0x5a, "]):
        path = tmp_path / f"demo{i}.yaml"
        path.write_text(demo.replace("algorithm: sum, ", f"algorithm: sum, {params}"), encoding="utf-8")
        prints.add(fingerprint(compile_schema(path)))
    assert len(prints) == 5
