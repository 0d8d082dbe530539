#pragma once
// A double in fixed notation with a given number of decimals, exactly as printf's "%.*f" (and
// std::to_chars with chars_format::fixed) writes it: the exact binary value rounded half to
// even. Run outputs write hundreds of such values per row; for decimals up to 9 and magnitudes
// under 1e15 this takes an integer path (the value's mantissa times 10^decimals in 128 bits,
// shifted by its exponent) about five times cheaper than the general conversion, which covers
// the rest.

#include <string>

namespace vcockpit {

// Writes v into [first, last) and returns one past the last character written, or nullptr
// when it does not fit (at most 330 characters are needed for any double).
char* write_fixed(char* first, char* last, double v, int decimals);

// Appends v to `out` (the same characters).
void append_fixed(std::string& out, double v, int decimals);

}  // namespace vcockpit
