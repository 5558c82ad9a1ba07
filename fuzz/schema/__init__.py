"""Schema-space fuzzing: random valid schemas over the language, each built for
every target and checked end to end (fuzz/schema/check.py), and random
mutations of them, each refused at a file:line or built correctly. Each schema's
C runs once (gcc -O0, UBSan) and is compiled at other compilers and optimisation
levels too: at one of seven chosen by the seed (`--c-matrix rotate`, the default),
or at all seven (`full`, about twice as long as rotate); see check.py.

    python3 -m fuzz.schema --count N [--seed S] [--jobs J] [--c-matrix rotate|full] [--record]
    python3 -m fuzz.schema --seed S --show
"""
