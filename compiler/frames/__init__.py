"""Working with frames on a link: `codeword decode`, `encode` and `monitor`.

Each command builds the schema's Python codec in memory (as `check` does) and
shows messages as rows of named values: enum and flag members by name, numbers
with their units, errors with the field and offset the codec names."""
