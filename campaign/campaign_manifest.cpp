#include "campaign/campaign_manifest.hpp"

#include <chrono>
#include <ctime>
#include <fstream>
#include <iostream>

#include "run/ensemble_output.hpp"

namespace granjet {

CampaignManifest::CampaignManifest(const std::filesystem::path& dir)
    : file_(dir / "manifest.json") {
  if (std::filesystem::exists(file_)) {
    try {
      std::ifstream in(file_);
      json_ = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      const std::filesystem::path broken = file_.string() + ".broken";
      std::cerr << "granjet: " << file_.string() << " is not readable JSON (" << e.what()
                << "); kept as " << broken.string() << ", a new manifest begins\n";
      std::filesystem::rename(file_, broken);
      json_ = nlohmann::json();
    }
  }
  if (!json_.is_object()) json_ = nlohmann::json::object();
  for (const char* key : {"runs", "ensembles"})
    if (!json_.contains(key) || !json_[key].is_object()) json_[key] = nlohmann::json::object();
  if (!json_.contains("invocations") || !json_["invocations"].is_array())
    json_["invocations"] = nlohmann::json::array();
}

void CampaignManifest::save() const { write_json_atomically(file_, json_); }

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace granjet
