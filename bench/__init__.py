"""Benchmarks of codeword against the tools users would otherwise pick.

Run `python3 -m bench` from the repository root; it writes bench/RESULTS.md.
"""
