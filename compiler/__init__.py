"""codeword: declarative protocol schemas compiled to codecs, headers and docs."""

__version__ = "0.1.0"
