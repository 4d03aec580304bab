// Seed lists as users write them, on the command line (--seeds) and in campaign files (seeds =).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace granjet {

// Ensembles are tens of seeds; ten thousand is a typo's worth.
inline constexpr std::uint64_t kMaxSeeds = 10000;

// "1..10" (inclusive) or "3,7,9", at most kMaxSeeds distinct seeds. Throws InputError naming
// `key`.
std::vector<std::uint64_t> parse_seeds(const std::string& text, const std::string& key);

}  // namespace granjet
