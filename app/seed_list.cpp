#include "app/seed_list.hpp"

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
    if (last < first || last - first > 10000) throw bad();
    for (std::uint64_t s = first; s <= last; ++s) seeds.push_back(s);
    return seeds;
  }
  std::size_t start = 0;
  for (std::size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
    seeds.push_back(number(text.substr(start, comma - start)));
  seeds.push_back(number(text.substr(start)));
  return seeds;
}

}  // namespace granjet
