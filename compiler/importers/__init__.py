"""Importers: specifications in other formats written out as codeword schemas that a
person can read and keep editing (`codeword import FORMAT FILE --out DIR`)."""
