"""Schema-space fuzzing: random valid schemas over the language, each built for
every target and checked end to end (fuzz/schema/check.py), and random
mutations of them, each refused at a file:line or built correctly.

    python3 -m fuzz.schema --count N [--seed S] [--jobs J] [--record]
    python3 -m fuzz.schema --seed S --show
"""
