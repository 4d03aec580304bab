// Seed lists as users write them, on the command line (--seeds) and in campaign files (seeds =).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace granjet {

// "1..10" (inclusive, at most 10,001 seeds) or "3,7,9". Throws InputError naming `key`.
std::vector<std::uint64_t> parse_seeds(const std::string& text, const std::string& key);

}  // namespace granjet
