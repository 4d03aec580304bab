#include "analysis/analysis_json.hpp"

#include <cmath>
#include <string>

namespace granjet::analysis {
namespace {

using nlohmann::json;

// The object at a dotted path, created on the way: "stress.rz" -> root["stress"]["rz"].
json& slot(json& root, const std::string& dotted) {
  json* node = &root;
  std::size_t start = 0;
  for (std::size_t dot; (dot = dotted.find('.', start)) != std::string::npos; start = dot + 1)
    node = &(*node)[dotted.substr(start, dot - start)];
  return (*node)[dotted.substr(start)];
}

// JSON has no NaN or infinity: what could not be measured is null.
json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json spread(const Spread& s) {
  return {
      {"mean", number(s.mean)}, {"std", number(s.std)}, {"sem", number(s.sem)}, {"count", s.count}};
}

// A distribution: its abscissa as a plain array, every other column as arrays of mean/std/sem.
json distribution(const EnsembleTable& table, const std::string& abscissa) {
  json out = json::object();
  for (const std::string& name : table.names()) {
    json& node = slot(out, name);
    for (std::size_t row = 0; row < table.rows(); ++row) {
      const Spread& s = table.at(row, name);
      if (name == abscissa) {
        node.push_back(number(s.mean));
      } else {
        node["mean"].push_back(number(s.mean));
        node["std"].push_back(number(s.std));
        node["sem"].push_back(number(s.sem));
      }
    }
  }
  return out;
}

}  // namespace

json to_json(const FitResult& fit) {
  json parameters = json::object();
  for (std::size_t k = 0; k < fit.parameters.size(); ++k)
    parameters[fit.parameters[k]] = {{"value", number(fit.value[k])},
                                     {"error", number(fit.error[k])}};
  return {{"parameters", parameters},
          {"ssr", number(fit.ssr)},
          {"points", fit.points},
          {"converged", fit.converged}};
}

json to_json(const EnsembleResult& result) {
  json out;
  out["dimension"] = result.dimension;
  out["seeds"] = result.seeds;
  out["coordinates"] = result.dimension == 3 ? "cylindrical" : "cartesian";
  out["mesh"] = {{"lateral", result.edges.lateral}, {"height", result.edges.height}};

  json bins = json::array();
  for (std::size_t row = 0; row < result.layout.rows(); ++row) {
    json bin;
    for (const std::string& name : result.layout.names())
      bin[name] = number(result.layout.at(row, name));
    const int layer = static_cast<int>(result.layout.at(row, "layer"));
    bin["layer"] = layer;
    bin["lateral_index"] = static_cast<int>(result.layout.at(row, "lateral_index"));
    bin["layer_name"] = std::string(1, static_cast<char>('a' + layer));
    for (const std::string& name : result.fields.names())
      slot(bin, name) = spread(result.fields.at(row, name));
    bins.push_back(std::move(bin));
  }
  out["bins"] = std::move(bins);

  json global = json::object();
  for (const std::string& name : result.global.names())
    slot(global, name) = spread(result.global.at(0, name));
  out["global"] = std::move(global);
  out["vdf"] = distribution(result.vdf, "c");
  if (result.azimuth.rows() > 0) out["azimuth"] = distribution(result.azimuth, "phi");

  json fits = json::object();
  for (const FitResult& fit : result.fits) fits[fit.law] = to_json(fit);
  out["fits"] = std::move(fits);
  return out;
}

}  // namespace granjet::analysis
