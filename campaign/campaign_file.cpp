#include "campaign/campaign_file.hpp"

#include <algorithm>
#include <boost/program_options.hpp>
#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>

#include "core/errors.hpp"
#include "run/seed_list.hpp"

namespace granjet {
namespace {

namespace po = boost::program_options;

constexpr const char* kCampaignSection = "campaign";

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r"), last = s.find_last_not_of(" \t\r");
  return first == std::string::npos ? "" : s.substr(first, last - first + 1);
}

// "a, b ,c" -> {"a", "b", "c"}; an empty item is refused.
std::vector<std::string> split_list(const std::string& text, const std::string& key) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    items.push_back(trim(text.substr(start, comma - start)));
    if (items.back().empty()) throw InputError(key, "'" + text + "' has an empty item");
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

bool valid_group_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
  return true;
}

// The section headers in file order. Program_options joins "[a.b] c" and "[a] b.c" alike, so a
// group name must not hold a dot; say so here rather than misread the keys.
std::vector<std::string> section_names(const std::string& text, const std::string& source) {
  std::vector<std::string> names;
  std::istringstream lines(text);
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    line = trim(line.substr(0, line.find('#')));
    if (line.empty() || line.front() != '[') continue;
    const std::string name = trim(line.substr(1, line.find(']') - 1));
    if (line.back() != ']' || !valid_group_name(name))
      throw InputError(source + ":" + std::to_string(number),
                       "'" + line + "' is not a section [name] of letters, digits, _ and -");
    for (const std::string& seen : names)
      if (seen == name)
        throw InputError("[" + name + "]", "the section appears twice in " + source);
    names.push_back(name);
  }
  return names;
}

double parse_fraction(const std::string& key, const std::string& text) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !(v > 0.0 && v <= 1.0))
    throw InputError(key, "'" + text + "' is not a number in (0, 1]");
  return v;
}

// The keys that a group or [campaign] may set besides scene keys.
struct Defaults {
  std::string backend = "soft_dem";
  std::vector<std::uint64_t> seeds;  // empty: the scene's run.seed
  double quick_fraction = 0.1;
};

// Applies one of the keys shared by [campaign] and groups; false when `key` is not one of them.
bool set_shared(Defaults& d, std::string& description, const std::string& key,
                const std::string& value, const std::string& where) {
  if (key == "backend")
    d.backend = value;
  else if (key == "seeds")
    d.seeds = parse_seeds(value, where);
  else if (key == "quick_fraction")
    d.quick_fraction = parse_fraction(where, value);
  else if (key == "description")
    description = value;
  else
    return false;
  return true;
}

}  // namespace

CampaignFile parse_campaign(std::istream& in, const std::filesystem::path& source,
                            const std::filesystem::path& base) {
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::vector<std::string> sections = section_names(text, source.string());

  std::istringstream config(text);
  po::options_description none;
  po::parsed_options parsed(&none);
  try {
    parsed = po::parse_config_file(config, none, /*allow_unregistered=*/true);
  } catch (const po::error& e) {
    throw InputError(source.string(), e.what());
  }
  // Key/value pairs by section, in file order.
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> entries;
  for (const po::option& o : parsed.options) {
    const auto dot = o.string_key.find('.');
    if (dot == std::string::npos)
      throw InputError(o.string_key, "stands outside any section in " + source.string() +
                                         "; put it under [campaign] or a [group]");
    auto& section = entries[o.string_key.substr(0, dot)];
    const std::string key = o.string_key.substr(dot + 1);
    for (const auto& [seen, value] : section)
      if (seen == key)
        throw InputError("[" + o.string_key.substr(0, dot) + "] " + key, "is set twice");
    section.emplace_back(key, o.value.empty() ? "" : trim(o.value.front()));
  }

  for (const auto& [section, keys] : entries)
    if (std::find(sections.begin(), sections.end(), section) == sections.end())
      throw InputError(section + "." + keys.front().first,
                       "stands outside any section in " + source.string() +
                           "; put it under [campaign] or a [group]");

  CampaignFile c;
  c.file = source;
  c.name = source.stem().string();
  Defaults defaults;
  for (const auto& [key, value] : entries[kCampaignSection]) {
    const std::string where = std::string("[") + kCampaignSection + "] " + key;
    if (key == "name")
      c.name = value;
    else if (!set_shared(defaults, c.description, key, value, where))
      throw InputError(where,
                       "unknown key; [campaign] allows name, description, seeds, backend, "
                       "quick_fraction");
  }

  for (const std::string& name : sections) {
    if (name == kCampaignSection) continue;
    CampaignGroup g;
    g.name = name;
    Defaults d = defaults;
    for (const auto& [key, value] : entries[name]) {
      const std::string where = "[" + name + "] " + key;
      if (key == "scene")
        g.scene = base / value;
      else if (key == "results")
        g.results = split_list(value, where);
      else if (set_shared(d, g.description, key, value, where))
        continue;
      else if (key.find('.') != std::string::npos)
        g.keys.push_back({key, split_list(value, where)});  // checked against the scene's keys
      else
        throw InputError(where,
                         "unknown key; a group allows scene, results, seeds, backend, "
                         "description, quick_fraction and scene keys section.key");
    }
    if (g.scene.empty()) throw InputError("[" + name + "] scene", "missing: which scene file?");
    if (g.results.empty())
      throw InputError("[" + name + "] results", "missing: which result ids (docs/model.md §7)?");
    g.backend = d.backend;
    g.seeds = d.seeds;
    g.quick_fraction = d.quick_fraction;
    c.groups.push_back(std::move(g));
  }
  if (c.groups.empty()) throw InputError(source.string(), "the campaign has no group");
  return c;
}

CampaignFile load_campaign(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open the campaign file");
  return parse_campaign(in, file, file.parent_path());
}

}  // namespace granjet
