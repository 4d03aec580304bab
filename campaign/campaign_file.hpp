// Campaign files: many runs of the study described in one INI file, read with the scene files'
// parser (Boost.Program_options config syntax) and checked against the scene key table.
//
//   [campaign]                      # defaults for every group
//   name = thesis
//   seeds = 1..10                   # or 1,4,7
//   backend = soft_dem
//   quick_fraction = 0.1            # --quick: run.t_end and the analysis window times this
//
//   [rheology3d]                    # a group: letters, digits, _ and -
//   results = F5.3, F5.5, F5.7      # the result ids (model §7) it serves
//   scene = ../scenes/jet3d.ini     # relative to the campaign file
//   contact.friction = 0, 0.2       # a scene key with several values is swept;
//   jet.phi_tilde = 0.3, 0.5, 0.9   # several swept keys make their product
//   wall.kind = fixed               # one value is a fixed override, as --set
//   seeds = 1..5                    # optional: the group's own seeds, backend, quick_fraction
//   description = ...
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace granjet {

// A scene key with its values in file order: one value overrides, several are swept.
struct CampaignKey {
  std::string key;  // "section.key" of the scene key table
  std::vector<std::string> values;
};

struct CampaignGroup {
  std::string name;
  std::string description;
  std::filesystem::path scene;
  std::string backend;
  std::vector<std::uint64_t> seeds;
  std::vector<std::string> results;
  std::vector<CampaignKey> keys;  // in file order
  double quick_fraction = 0.1;
};

struct CampaignFile {
  std::filesystem::path file;
  std::string name;
  std::string description;
  std::vector<CampaignGroup> groups;  // in file order
};

// Throws InputError naming the group and key ("[group] key") and what is allowed. Scene keys and
// their values are checked when the runs are planned (campaign_plan.hpp), against the scene.
CampaignFile load_campaign(const std::filesystem::path& file);
// `base`: the directory that relative scene paths start from.
CampaignFile parse_campaign(std::istream& in, const std::filesystem::path& source,
                            const std::filesystem::path& base);

}  // namespace granjet
