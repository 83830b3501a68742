// toml++ is a header-only parser of some 17,000 lines: compiled here once, the files that read
// TOML see only its declarations (TOML_HEADER_ONLY=0), which halves their build time.
#define TOML_IMPLEMENTATION
#include <toml++/toml.h>
