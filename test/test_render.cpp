// Tests of the PNG writer and the mesh renderers (unsupported/Eigen/src/MeshTools/WritePNG.h,
// RenderMesh.h): the file is decoded here independently (chunk walk, CRC check, zlib inflate) and
// its size and pixels are compared with what was drawn; a flipped uv triangle must come out red.

#include <unsupported/Eigen/MeshTools>

#include <doctest/doctest.h>

#include <cstdio>
#include <fstream>
#include <iterator>

namespace {

/** A decoded 8-bit RGB PNG (only what writePNG produces: colour type 2, filter 0 rows). */
struct DecodedPng
{
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  std::array<std::uint8_t, 3> pixel(int x, int y) const
  {
    const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

std::uint32_t readUint32(const std::vector<std::uint8_t>& data, std::size_t at)
{
  return (std::uint32_t(data[at]) << 24) | (std::uint32_t(data[at + 1]) << 16) | (std::uint32_t(data[at + 2]) << 8) |
         std::uint32_t(data[at + 3]);
}

/** Decodes \a path; fails the test (and returns false) on any structural problem. */
bool decodePng(const std::string& path, DecodedPng& image)
{
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  const std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  REQUIRE(data.size() > 8);
  CHECK(std::equal(signature, signature + 8, data.begin()));
  std::vector<std::uint8_t> idat;
  bool sawEnd = false;
  for (std::size_t at = 8; at + 12 <= data.size();)
  {
    const std::uint32_t length = readUint32(data, at);
    REQUIRE(at + 12 + length <= data.size());
    const std::string type(data.begin() + long(at) + 4, data.begin() + long(at) + 8);
    const std::uint32_t crc = std::uint32_t(crc32(crc32(0L, Z_NULL, 0), &data[at + 4], uInt(4 + length)));
    CHECK(crc == readUint32(data, at + 8 + length));
    const std::size_t body = at + 8;
    if (type == "IHDR")
    {
      image.width = int(readUint32(data, body));
      image.height = int(readUint32(data, body + 4));
      CHECK(data[body + 8] == 8); // bit depth
      CHECK(data[body + 9] == 2); // RGB
    }
    else if (type == "IDAT")
      idat.insert(idat.end(), data.begin() + long(body), data.begin() + long(body + length));
    else if (type == "IEND")
      sawEnd = true;
    at += 12 + length;
  }
  CHECK(sawEnd);
  const std::size_t rowBytes = std::size_t(image.width) * 3;
  std::vector<std::uint8_t> raw((rowBytes + 1) * std::size_t(image.height));
  uLongf rawSize = uLongf(raw.size());
  REQUIRE(uncompress(raw.data(), &rawSize, idat.data(), uLong(idat.size())) == Z_OK);
  REQUIRE(rawSize == raw.size());
  image.rgb.resize(rowBytes * std::size_t(image.height));
  for (int y = 0; y < image.height; ++y)
  {
    CHECK(raw[std::size_t(y) * (rowBytes + 1)] == 0);
    std::copy_n(&raw[std::size_t(y) * (rowBytes + 1) + 1], rowBytes, &image.rgb[std::size_t(y) * rowBytes]);
  }
  return true;
}

bool isRed(const std::array<std::uint8_t, 3>& p) { return p[0] > 200 && p[1] < 60 && p[2] < 60; }

} // namespace

TEST_CASE("writePNG round trip: size and every pixel")
{
  const int width = 37, height = 23;
  std::vector<std::uint8_t> rgb(std::size_t(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
    {
      const std::size_t i = (std::size_t(y) * width + x) * 3;
      rgb[i] = std::uint8_t(x * 7);
      rgb[i + 1] = std::uint8_t(y * 11);
      rgb[i + 2] = std::uint8_t((x * y) & 255);
    }
  const std::string path = "test_render_roundtrip.png";
  std::string error;
  REQUIRE(Eigen::writePNG(path, width, height, rgb, &error));
  DecodedPng image;
  REQUIRE(decodePng(path, image));
  CHECK(image.width == width);
  CHECK(image.height == height);
  CHECK(image.rgb == rgb);
  std::remove(path.c_str());
}

TEST_CASE("writePNG rejects bad input with a message")
{
  std::string error;
  CHECK_FALSE(Eigen::writePNG("x.png", 0, 5, {}, &error));
  CHECK(error.find("x.png") != std::string::npos);
  CHECK_FALSE(Eigen::writePNG("x.png", 2, 2, std::vector<std::uint8_t>(11), &error));
  CHECK(error.find("12") != std::string::npos);
  CHECK_FALSE(Eigen::writePNG("no-such-dir/x.png", 1, 1, std::vector<std::uint8_t>(3), &error));
  CHECK(error.find("no-such-dir/x.png") != std::string::npos);
}

TEST_CASE("renderUVCheckerboard: checkerboard inside, white outside, flipped triangle in red")
{
  // Two triangles side by side in uv: the left one counter-clockwise (the layout's orientation,
  // the larger one), the right one clockwise (flipped).
  Eigen::MatrixXd UV(6, 2);
  UV << 0, 0, 2, 0, 0, 2, //
      2.5, 0, 2.5, 1, 3.5, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 3, 4, 5;
  const std::string path = "test_render_uv.png";
  std::string error;
  const int size = 200;
  REQUIRE(Eigen::renderUVCheckerboard(UV, F, path, size, 4, &error));
  DecodedPng image;
  REQUIRE(decodePng(path, image));
  CHECK(image.width == size);
  CHECK(image.height == size);
  // Layout bounding box [0,3.5]x[0,2], scale 0.92*200/3.5, centred. Map uv to pixels the same way.
  const double scale = 0.92 * size / 3.5;
  auto pixelOf = [&](double u, double v) {
    return std::array<int, 2>{int(0.5 * size + scale * (u - 1.75)), int(0.5 * size - scale * (v - 1.0))};
  };
  const auto flippedCentre = pixelOf(2.5 + 1.0 / 3, 1.0 / 3);
  CHECK(isRed(image.pixel(flippedCentre[0], flippedCentre[1])));
  const auto goodCentre = pixelOf(0.45, 0.45);
  const auto good = image.pixel(goodCentre[0], goodCentre[1]);
  CHECK_FALSE(isRed(good));
  CHECK((good == std::array<std::uint8_t, 3>{235, 235, 235} || good == std::array<std::uint8_t, 3>{70, 110, 190}));
  // Checks of side 3.5/4: uv (0.3,0.3) and (1.2,0.3) lie in neighbouring squares: different colours.
  const auto p1 = pixelOf(0.3, 0.3), p2 = pixelOf(1.2, 0.3);
  CHECK(image.pixel(p1[0], p1[1]) != image.pixel(p2[0], p2[1]));
  // Outside every triangle the picture is white.
  const auto outside = pixelOf(1.8, 1.8);
  CHECK(image.pixel(outside[0], outside[1]) == std::array<std::uint8_t, 3>{255, 255, 255});
  std::remove(path.c_str());

  CHECK_FALSE(Eigen::renderUVCheckerboard(UV, F, path, 4, 4, &error));
  Eigen::MatrixXi badF(1, 3);
  badF << 0, 1, 6;
  CHECK_FALSE(Eigen::renderUVCheckerboard(UV, badF, path, 100, 4, &error));
  CHECK(error.find("out of range") != std::string::npos);
}

TEST_CASE("renderMeshShaded: z-buffer keeps the nearer triangle, background stays white")
{
  // Two overlapping squares-as-triangles facing the viewer: the near one (z = 1) tilted, so its
  // shade differs from the far one (z = 0).
  Eigen::MatrixXd V(6, 3);
  V << -1, -1, 0, 1, -1, 0, 0, 1, 0, //
      -1, -1, 1, 1, -1, 1.5, 0, 1, 1;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 3, 4, 5;
  const std::string path = "test_render_shaded.png";
  std::string error;
  REQUIRE(Eigen::renderMeshShaded(V, F, path, Eigen::Matrix3d::Identity(), 100, {5}, &error));
  DecodedPng image;
  REQUIRE(decodePng(path, image));
  CHECK(image.width == 100);
  const auto centre = image.pixel(50, 55);
  const auto corner = image.pixel(2, 2);
  CHECK(corner == std::array<std::uint8_t, 3>{255, 255, 255});
  // The near triangle's normal is tilted (|n.z| < 1), the far one faces the viewer: the centre
  // shows the darker, near one.
  CHECK(centre[2] < 225);
  CHECK(centre[2] > 100);
  // The highlighted top vertex (0, 1, 1) of the near triangle lies at pixel (50, 4): red dot.
  CHECK(isRed(image.pixel(50, 4)));
  std::remove(path.c_str());

  CHECK_FALSE(Eigen::renderMeshShaded(V, F, path, Eigen::Matrix3d::Identity(), 100, {7}, &error));
  CHECK(error.find("highlighted") != std::string::npos);
}

TEST_CASE("renderMeshCheckerboard: the uv checkerboard on the surface")
{
  // A unit square facing the viewer whose uv are its xy coordinates: 2 x 2 checks.
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 2, 3;
  const Eigen::MatrixXd UV = V.leftCols(2);
  const std::string path = "test_render_textured.png";
  std::string error;
  REQUIRE(Eigen::renderMeshCheckerboard(V, F, UV, path, Eigen::Matrix3d::Identity(), 100, 2, &error));
  DecodedPng image;
  REQUIRE(decodePng(path, image));
  // uv (0.25, 0.75) and (0.75, 0.75) are in different squares, (0.25, 0.25) and (0.75, 0.75) in
  // squares of the same colour. Pixel of uv (u, v): (4 + 92 u, 96 - 92 v).
  auto at = [&](double u, double v) { return image.pixel(int(4 + 92 * u), int(96 - 92 * v)); };
  CHECK(at(0.25, 0.75) != at(0.75, 0.75));
  CHECK(at(0.25, 0.25) == at(0.75, 0.75));
  CHECK(at(0.25, 0.25) != std::array<std::uint8_t, 3>{255, 255, 255});
  std::remove(path.c_str());
  CHECK_FALSE(Eigen::renderMeshCheckerboard(V, F, UV.topRows(3), path, Eigen::Matrix3d::Identity(), 100, 2, &error));
  CHECK(error.find("UV") != std::string::npos);
}
