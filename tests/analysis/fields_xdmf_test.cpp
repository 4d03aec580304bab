#include "analysis/fields_xdmf.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace granjet::analysis {
namespace {

namespace fs = std::filesystem;

// Two layers of three lateral bins, one field.
EnsembleResult ensemble(int dimension, double height_origin) {
  EnsembleResult e;
  e.dimension = dimension;
  e.seeds = 1;
  e.edges.lateral = dimension == 3 ? std::vector<double>{0.0, 1.0, 2.5, 4.0}
                                   : std::vector<double>{-3.0, -1.0, 1.0, 3.0};
  e.edges.height = {0.0, 5.0, 10.0};
  e.edges.height_origin = height_origin;
  Table fields(6);
  for (std::size_t bin = 0; bin < 6; ++bin) fields.set("stress.rz", bin, 0.5 * bin);
  e.fields = EnsembleTable(std::vector<Table>{fields});
  return e;
}

// Corner (s, l, k) of FieldCells::corners.
std::vector<double> corner(const FieldCells& cells, std::size_t s, std::size_t l, std::size_t k) {
  const std::size_t at = ((s * (cells.layers + 1) + l) * (cells.lateral + 1) + k) * 3;
  return {cells.corners[at], cells.corners[at + 1], cells.corners[at + 2]};
}

// 3D: each ring is revolved about the jet axis at its radii, from the height origin up.
TEST(FieldCells, RevolveRingsAboutTheJetAxis) {
  const EnsembleResult e = ensemble(3, 0.5);
  const FieldCells cells = field_cells(e);
  ASSERT_EQ(cells.sectors, kRingSectors);
  ASSERT_EQ(cells.layers, 2u);
  ASSERT_EQ(cells.lateral, 3u);
  ASSERT_EQ(cells.corners.size(), (kRingSectors + 1) * 3 * 4 * 3);
  for (std::size_t s = 0; s <= cells.sectors; ++s)
    for (std::size_t l = 0; l <= 2; ++l)
      for (std::size_t k = 0; k <= 3; ++k) {
        const std::vector<double> p = corner(cells, s, l, k);
        EXPECT_NEAR(std::hypot(p[0], p[1]), e.edges.lateral[k], 1e-12);
        EXPECT_EQ(p[2], 0.5 + e.edges.height[l]);
        if (k == 0) continue;  // the axis has no angle
        const double angle = 2.0 * std::numbers::pi * static_cast<double>(s) / kRingSectors;
        EXPECT_NEAR(std::remainder(std::atan2(p[1], p[0]) - angle, 2.0 * std::numbers::pi), 0.0,
                    1e-12);
      }
  // The last plane closes the ring exactly on the first.
  EXPECT_EQ(corner(cells, kRingSectors, 1, 3), corner(cells, 0, 1, 3));
}

// 2D: boxes at (origin + height, y), one grain diameter thick about the grains' plane z = 0.
TEST(FieldCells, Stand2DBinsWhereTheGrainsAre) {
  const EnsembleResult e = ensemble(2, 0.5);
  const FieldCells cells = field_cells(e);
  ASSERT_EQ(cells.sectors, 1u);
  ASSERT_EQ(cells.corners.size(), 2u * 3 * 4 * 3);
  for (std::size_t s = 0; s <= 1; ++s)
    for (std::size_t l = 0; l <= 2; ++l)
      for (std::size_t k = 0; k <= 3; ++k)
        EXPECT_EQ(corner(cells, s, l, k),
                  (std::vector<double>{0.5 + e.edges.height[l], e.edges.lateral[k],
                                       s == 0 ? -0.5 : 0.5}));
}

std::string fields_xmf(const EnsembleResult& e) {
  const fs::path dir =
      fs::temp_directory_path() / ("granjet_fields_xdmf_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  write_fields_xdmf(dir / "run.fields.xmf", "run.h5", e);
  std::ifstream in(dir / "run.fields.xmf");
  std::stringstream text;
  text << in.rdbuf();
  fs::remove_all(dir);
  return text.str();
}

bool has(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

// A structured grid on the stored corners; each field's means repeated per sector, spelt for
// the Xdmf3 readers (<Function>, '|') and for the Xdmf2 reader (Function DataItem, ';').
TEST(FieldsXdmf, DrawsTheStoredCellsWithTheMeansPerSector) {
  const std::string xmf = fields_xmf(ensemble(3, 0.0));
  const std::string sectors = std::to_string(kRingSectors);
  const std::string planes = std::to_string(kRingSectors + 1);
  EXPECT_TRUE(has(xmf, "<Topology TopologyType=\"3DSMesh\" Dimensions=\"" + planes + " 3 4\"/>"));
  EXPECT_TRUE(has(xmf, "<DataItem Dimensions=\"" + planes +
                           " 3 4 3\" NumberType=\"Float\" Precision=\"8\" "
                           "Format=\"HDF\">run.h5:/fields/mesh/points</DataItem>"));
  EXPECT_TRUE(has(xmf, "<Attribute Name=\"stress.rz\" AttributeType=\"Scalar\" Center=\"Cell\">"));
  std::string join3 = "$0", join2 = "$0";
  for (std::size_t s = 1; s < kRingSectors; ++s) {
    join3 += "|$0";
    join2 += ";$0";
  }
  EXPECT_TRUE(has(xmf, "<Function ItemType=\"Function\" Function=\"" + join3 + "\""));
  EXPECT_TRUE(has(xmf, "<DataItem ItemType=\"Function\" Function=\"" + join2 + "\" Dimensions=\"" +
                           sectors + " 2 3\">"));
  EXPECT_TRUE(has(xmf, "\"HDF\">run.h5:/fields/stress/rz/mean</DataItem>"));
}

TEST(FieldsXdmf, Draws2DBinsOnce) {
  const std::string xmf = fields_xmf(ensemble(2, 0.0));
  EXPECT_TRUE(has(xmf, "<Topology TopologyType=\"3DSMesh\" Dimensions=\"2 3 4\"/>"));
  EXPECT_TRUE(has(xmf, "<DataItem ItemType=\"Function\" Function=\"$0\" Dimensions=\"1 2 3\">"));
}

}  // namespace
}  // namespace granjet::analysis
