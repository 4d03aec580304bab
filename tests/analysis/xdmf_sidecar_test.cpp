#include "analysis/xdmf_sidecar.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace granjet::analysis {
namespace {

namespace fs = std::filesystem;

// The XML is checked as text: the readers themselves are exercised by
// tests/interop/paraview_check.py, which needs ParaView.
class XdmfSidecarTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("granjet_xdmf_sidecar_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const XdmfLayout& layout, const std::vector<XdmfFrame>& frames,
                    const std::string& h5_name = "run.h5") {
    const fs::path xmf = dir_ / "run.xmf";
    write_xdmf_sidecar(xmf, h5_name, layout, frames);
    std::ifstream in(xmf);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  fs::path dir_;
};

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

bool has(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

XdmfLayout layout3(std::size_t contact_rows = 0) {
  XdmfLayout layout;
  layout.dimension = 3;
  layout.rows = 5;
  layout.contact_rows = contact_rows;
  return layout;
}

TEST_F(XdmfSidecarTest, OneGrainGridPerFrameWithGrainsAtItsExactTime) {
  const std::string xmf = write(layout3(), {{0.1 + 0.2, 3, 0}, {0.5, 0, 0}, {0.7, 2, 0}});
  EXPECT_EQ(count(xmf, "<Grid Name=\"grains\" GridType=\"Uniform\">"), 2u);
  EXPECT_TRUE(has(xmf, "<Time Value=\"0.30000000000000004\"/>"));
  EXPECT_FALSE(has(xmf, "<Time Value=\"0.5\"/>")) << "a frame without grains draws nothing";
  EXPECT_TRUE(has(xmf, "<Time Value=\"0.7\"/>"));
  EXPECT_TRUE(has(xmf, "CollectionType=\"Temporal\""));
  EXPECT_FALSE(has(xmf, "Spatial"));
  EXPECT_FALSE(has(xmf, "contacts"));
}

// Only the present grains are cells: the first `grains` entries of the frame's present list,
// in both readers' spellings of the selection, over the frame's full rows of positions.
TEST_F(XdmfSidecarTest, SelectsThePresentGrainsOverTheFullRows) {
  const std::string xmf = write(layout3(), {{0.0, 5, 0}, {1.0, 3, 0}});
  EXPECT_TRUE(has(xmf, "<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"3\""));
  EXPECT_TRUE(has(xmf, "run.h5:/particles/all/present/value|1 0:1 1:1 3:2 5\n"));
  EXPECT_TRUE(has(xmf, "<DataItem Dimensions=\"3 2\" Format=\"XML\">1 0 1 1 1 3</DataItem>"));
  EXPECT_TRUE(has(xmf, "run.h5:/particles/all/position/value|1 0 0:1 1 1:1 5 3:2 5 3\n"));
  EXPECT_TRUE(has(xmf, "<DataItem Dimensions=\"3 3\" Format=\"XML\">1 0 0 1 1 1 1 5 3</DataItem>"));
  EXPECT_TRUE(has(xmf,
                  "<DataItem Dimensions=\"2 5 3\" NumberType=\"Float\" Precision=\"8\" "
                  "Format=\"HDF\">run.h5:/particles/all/position/value</DataItem>"));
  EXPECT_TRUE(has(xmf, "<Geometry GeometryType=\"XYZ\">"));
  // Xdmf2 reads Type (not ItemType) as a hyperslab; Xdmf3 must not see one.
  EXPECT_TRUE(has(xmf, "<DataItem Type=\"HyperSlab\""));
  EXPECT_FALSE(has(xmf, "ItemType"));
}

TEST_F(XdmfSidecarTest, GrainAttributesFollowTheLayout) {
  XdmfLayout layout = layout3();
  std::string xmf = write(layout, {{0.0, 5, 0}});
  for (const char* name : {"velocity\" AttributeType=\"Vector\"",
                           "radius\" AttributeType=\"Scalar\"", "id\" AttributeType=\"Scalar\""})
    EXPECT_TRUE(has(xmf, std::string("<Attribute Name=\"") + name + " Center=\"Node\">")) << name;
  EXPECT_TRUE(
      has(xmf, "NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">run.h5:/particles/all/id"));
  EXPECT_FALSE(has(xmf, "omega"));
  EXPECT_FALSE(has(xmf, "force"));

  layout.omega = layout.force = true;
  xmf = write(layout, {{0.0, 5, 0}});
  EXPECT_TRUE(has(xmf, "<Attribute Name=\"omega\" AttributeType=\"Vector\""));
  EXPECT_TRUE(has(xmf, "<Attribute Name=\"force\" AttributeType=\"Vector\""));

  layout.dimension = 2;  // a disk's spin is a scalar
  xmf = write(layout, {{0.0, 5, 0}});
  EXPECT_TRUE(has(xmf, "<Attribute Name=\"omega\" AttributeType=\"Scalar\""));
  EXPECT_TRUE(has(xmf, "<Geometry GeometryType=\"XY\">"));
  EXPECT_TRUE(has(xmf, "run.h5:/particles/all/velocity/value|0 0 0:1 1 1:1 5 2:1 5 2\n"));
}

TEST_F(XdmfSidecarTest, ContactsAreLinesInFramesThatHaveThem) {
  const std::string xmf = write(layout3(7), {{0.0, 5, 0}, {1.0, 4, 6}});
  EXPECT_EQ(count(xmf, "CollectionType=\"Spatial\""), 2u);
  EXPECT_EQ(count(xmf, "<Grid Name=\"grains\""), 2u);
  EXPECT_EQ(count(xmf, "<Grid Name=\"contacts\""), 1u) << "frame 0 has no contacts";
  EXPECT_TRUE(has(xmf,
                  "<Topology TopologyType=\"Polyline\" NumberOfElements=\"6\" "
                  "NodesPerElement=\"2\">"));
  EXPECT_TRUE(has(xmf, "run.h5:/connectivity/contacts/value|1 0 0:1 1 1:1 6 2:2 7 2\n"));
  for (const char* name :
       {"normal_force\" AttributeType=\"Vector\"", "tangential_force\" AttributeType=\"Vector\"",
        "overlap\" AttributeType=\"Scalar\""})
    EXPECT_TRUE(has(xmf, std::string("<Attribute Name=\"") + name + " Center=\"Cell\">")) << name;
  EXPECT_TRUE(has(xmf, "run.h5:/contacts/overlap/value|1 0:1 1:1 6:2 7\n"));
  // The lines join rows of the frame's full position row, like the grains.
  EXPECT_EQ(count(xmf, "run.h5:/particles/all/position/value|1 0 0:1 1 1:1 5 3:2 5 3\n"), 2u);
}

TEST_F(XdmfSidecarTest, IsBalancedAndNamesTheFileEscaped) {
  const std::string xmf = write(layout3(7), {{0.0, 5, 3}, {1.0, 4, 6}}, "a&b.h5");
  EXPECT_EQ(count(xmf, "<DataItem "), count(xmf, "</DataItem>"));
  EXPECT_EQ(count(xmf, "<Grid "), count(xmf, "</Grid>"));
  EXPECT_EQ(count(xmf, "<Attribute "), count(xmf, "</Attribute>"));
  EXPECT_TRUE(has(xmf, ">a&amp;b.h5:/particles/all/position/value|"));
  EXPECT_FALSE(has(xmf, "a&b"));
}

}  // namespace
}  // namespace granjet::analysis
