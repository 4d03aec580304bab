#include "run/seed_list.hpp"

#include <algorithm>
#include <charconv>

#include "core/errors.hpp"

namespace granjet {

std::vector<std::uint64_t> parse_seeds(const std::string& text, const std::string& key) {
  const auto bad = [&] {
    return InputError(key, "'" + text + "' is not a range A..B (A <= B) or a list a,b,c");
  };
  const auto number = [&](std::string s) {
    const auto first = s.find_first_not_of(' '), last = s.find_last_not_of(' ');
    s = first == std::string::npos ? "" : s.substr(first, last - first + 1);
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || s.empty()) throw bad();
    return v;
  };
  std::vector<std::uint64_t> seeds;
  if (const auto dots = text.find(".."); dots != std::string::npos) {
    const std::uint64_t first = number(text.substr(0, dots)), last = number(text.substr(dots + 2));
    if (last < first) throw bad();
    if (last - first >= kMaxSeeds)
      throw InputError(key, "'" + text + "' is " + std::to_string(last - first) +
                                " + 1 seeds; at most " + std::to_string(kMaxSeeds));
    // Counted, not compared with `last`: a range ending at the largest seed must not wrap.
    for (std::uint64_t k = 0; k <= last - first; ++k) seeds.push_back(first + k);
    return seeds;
  }
  std::size_t start = 0;
  for (std::size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
    seeds.push_back(number(text.substr(start, comma - start)));
  seeds.push_back(number(text.substr(start)));
  if (seeds.size() > kMaxSeeds)
    throw InputError(key,
                     std::to_string(seeds.size()) + " seeds; at most " + std::to_string(kMaxSeeds));
  std::vector<std::uint64_t> sorted = seeds;
  std::sort(sorted.begin(), sorted.end());
  if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
    throw InputError(
        key, "seed " + std::to_string(*twice) + " is listed twice (its runs would share a file)");
  return seeds;
}

}  // namespace granjet
