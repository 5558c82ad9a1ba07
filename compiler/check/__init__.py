"""`codeword check`: hold data up against a schema with the schema's own generated codec."""
from .finding import Finding
from .report import JSON_FORMAT_VERSION, JsonReport, TextReport
from .run import INPUT_FORMATS, Options, UsageError, check, load_codec, plan
from .sources import Tally

__all__ = ["Finding", "JSON_FORMAT_VERSION", "JsonReport", "TextReport", "INPUT_FORMATS", "Options",
           "UsageError", "check", "load_codec", "plan", "Tally"]
