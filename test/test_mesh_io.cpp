// Mesh readers and writers of unsupported/Eigen/MeshTools: exact round trips through every format
// (OFF, OBJ, ascii PLY, binary PLY; plain and gzip), hand-written files exercising the format
// details (OBJ corner forms and negative references, PLY property types, both byte orders, extra
// elements), one test per kind of malformed file (false + message naming file and line / byte,
// outputs untouched), and a fuzz test that mutates valid files thousands of times with fixed seeds
// (set UC_MESH_FUZZ_ROUNDS for a longer run, e.g. under -fsanitize=address,undefined).
#include <doctest/doctest.h>

#include <unsupported/Eigen/MeshTools>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#ifndef UC_TEST_DATA_DIR
#error "UC_TEST_DATA_DIR must name the project's data folder"
#endif

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::MatrixXi;

/** A fresh scratch folder for this test program, removed at exit. */
struct ScratchFolder {
  std::string path;
  ScratchFolder() {
    const auto folder = std::filesystem::temp_directory_path() /
                        ("uc_test_mesh_io_" + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(folder);
    path = folder.string();
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

std::string scratchDir() {
  static const ScratchFolder folder;
  return folder.path;
}

std::string scratchPath(const std::string& name) { return scratchDir() + "/" + name; }

/** Writes \a bytes to \a name in the scratch folder (gzip-compressed if \a gzip) and returns the path. */
std::string writeFile(const std::string& name, const std::string& bytes, bool gzip = false) {
  const std::string path = scratchPath(name);
  // A new file rather than a truncated one: ext4 flushes truncated-and-rewritten files on close.
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  if (gzip) {
    gzFile file = gzopen(path.c_str(), "wb");
    REQUIRE(file != nullptr);
    if (!bytes.empty()) REQUIRE(gzwrite(file, bytes.data(), unsigned(bytes.size())) == int(bytes.size()));
    REQUIRE(gzclose(file) == Z_OK);
  } else {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    REQUIRE(out.good());
  }
  return path;
}

/** An icosphere with irregular coordinates (so that printing must keep every digit). */
void testMesh(MatrixXd& V, MatrixXi& F) {
  Eigen::icosphereMesh(1, V, F);
  std::mt19937 generator(11);
  std::uniform_real_distribution<double> scale(0.5, 1.5);
  for (Index i = 0; i < V.rows(); ++i) V.row(i) *= scale(generator) * 1e-3 * double(i + 1);
}

/** Binary writer for hand-made PLY bodies: values in the given byte order. */
struct ByteWriter {
  bool bigEndian;
  std::string bytes;
  template <typename T>
  void put(T value) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    const std::uint16_t probe = 1;
    const bool hostLittle = *reinterpret_cast<const unsigned char*>(&probe) == 1;
    if (hostLittle == bigEndian) std::reverse(raw, raw + sizeof(T));
    bytes.append(reinterpret_cast<const char*>(raw), sizeof(T));
  }
};

/** Expects readMesh to fail on \a path with a message containing the path and each of \a parts,
  * leaving V and F untouched. */
void expectReadFailure(const std::string& path, const std::vector<std::string>& parts) {
  MatrixXd V = MatrixXd::Constant(1, 3, 42.0);
  MatrixXi F = MatrixXi::Constant(1, 3, 42);
  std::string error;
  INFO("file: " << path);
  CHECK_FALSE(Eigen::readMesh(path, V, F, &error));
  INFO("error: " << error);
  CHECK(error.find(path) != std::string::npos);
  for (const std::string& part : parts) CHECK(error.find(part) != std::string::npos);
  CHECK(V == MatrixXd::Constant(1, 3, 42.0));
  CHECK(F == MatrixXi::Constant(1, 3, 42));
}

/** Reads \a path and requires success. */
void readOrFail(const std::string& path, MatrixXd& V, MatrixXi& F) {
  std::string error;
  const bool ok = Eigen::readMesh(path, V, F, &error);
  INFO(error);
  REQUIRE(ok);
  CHECK(error.empty());
}

} // namespace

TEST_CASE("writeMesh/readMesh: exact round trips through every format, plain and gzip") {
  MatrixXd V;
  MatrixXi F;
  testMesh(V, F);
  for (const std::string extension : {".off", ".obj", ".ply", ".OBJ"})
    for (const bool binary : {false, true})
      for (const bool gzip : {false, true}) {
        if (binary && extension != ".ply") continue;
        const std::string path = scratchPath(std::string("roundtrip") + (binary ? "_bin" : "") + extension + (gzip ? ".gz" : ""));
        INFO(path);
        std::string error = "stale";
        REQUIRE(Eigen::writeMesh(path, V, F, &error, binary));
        CHECK(error.empty());
        // .gz really compresses, the plain file really is plain.
        std::ifstream raw(path, std::ios::binary);
        unsigned char magic[2] = {0, 0};
        raw.read(reinterpret_cast<char*>(magic), 2);
        CHECK((magic[0] == 0x1f && magic[1] == 0x8b) == gzip);
        MatrixXd V2;
        MatrixXi F2;
        readOrFail(path, V2, F2);
        CHECK(V2 == V);
        CHECK(F2 == F);
      }

  // Planar input (2 columns) is written with z = 0; an empty mesh round-trips too.
  MatrixXd UV = V.leftCols(2);
  REQUIRE(Eigen::writeMesh(scratchPath("planar.ply"), UV, F, nullptr, true));
  MatrixXd V2;
  MatrixXi F2;
  readOrFail(scratchPath("planar.ply"), V2, F2);
  CHECK(V2.leftCols(2) == UV);
  CHECK(V2.col(2).isZero(0));
  REQUIRE(Eigen::writeMesh(scratchPath("empty.obj"), MatrixXd(0, 3), MatrixXi(0, 3)));
  readOrFail(scratchPath("empty.obj"), V2, F2);
  CHECK(V2.rows() == 0);
  CHECK(F2.rows() == 0);
}

TEST_CASE("readMesh: the shipped OFF file reads like readOFF; content sniffing") {
  const std::string path = std::string(UC_TEST_DATA_DIR) + "/camelhead.off.gz";
  MatrixXd V1, V2;
  MatrixXi F1, F2;
  REQUIRE(Eigen::readOFF(path, V1, F1));
  readOrFail(path, V2, F2);
  CHECK(V1 == V2);
  CHECK(F1 == F2);
  CHECK(F1.rows() > 20000);

  // Through every writer and back, the real mesh survives exactly.
  REQUIRE(Eigen::writeMesh(scratchPath("camel.ply.gz"), V1, F1, nullptr, true));
  readOrFail(scratchPath("camel.ply.gz"), V2, F2);
  CHECK(V1 == V2);
  CHECK(F1 == F2);

  // Names without a known extension: the content decides.
  MatrixXd V;
  MatrixXi F;
  testMesh(V, F);
  for (const std::string format : {"off", "obj", "ply"}) {
    REQUIRE(Eigen::writeMesh(scratchPath("sniff." + format + ".gz"), V, F));
    std::filesystem::rename(scratchPath("sniff." + format + ".gz"), scratchPath("sniff_" + format + ".gz"));
    readOrFail(scratchPath("sniff_" + format + ".gz"), V2, F2);
    CHECK(V2 == V);
    CHECK(F2 == F);
  }
  expectReadFailure(writeFile("unknown.gz", "hello world\n", true), {"unknown mesh format"});
  expectReadFailure(scratchPath("does_not_exist.obj"), {"cannot open"});
  expectReadFailure(scratchPath("does_not_exist.dat"), {"cannot open"});
}

TEST_CASE("readOBJ: corner forms, negative references, polygons, ignored records") {
  const std::string obj =
      "# a quad and a triangle\n"
      "mtllib scene.mtl\no thing\ng group\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0 1.0\n"
      "vt 0 0\nvt 1 0\nvn 0 0 1\n"
      "v 0 1 0 0.5 0.5 0.5   # with a colour\n"
      "usemtl red\ns off\n"
      "f 1/1/1 2/2/1 3//1 4/1\n"
      "v 2 0 0\n"
      "f -4 -1 -3\n"
      "l 1 2\n\n   \n";
  MatrixXd V;
  MatrixXi F;
  readOrFail(writeFile("corners.obj", obj), V, F);
  MatrixXd expectedV(5, 3);
  expectedV << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0;
  MatrixXi expectedF(3, 3);
  expectedF << 0, 1, 2, 0, 2, 3, 1, 4, 2;
  CHECK(V == expectedV);
  CHECK(F == expectedF);
}

TEST_CASE("readPLY: property types, both byte orders, extra properties and elements") {
  // The same mesh as ascii, little- and big-endian: vertex x (float), y (short), z (double) among
  // other properties; faces with a ushort count and uint indices; a triangle and a quad.
  const std::string header =
      "ply\nformat %s 1.0\ncomment hand made\nobj_info test\n"
      "element material 2\nproperty uchar id\nproperty list uchar float weights\n"
      "element vertex 4\nproperty uchar red\nproperty float x\nproperty int16 y\nproperty double z\n"
      "element face 2\nproperty int flags\nproperty list ushort uint vertex_indices\n"
      "element edge 0\nproperty int vertex1\n"
      "element empty 5\n"
      "end_header\n";
  auto headerFor = [&](const std::string& format) {
    std::string h = header;
    h.replace(h.find("%s"), 2, format);
    return h;
  };
  MatrixXd expectedV(4, 3);
  expectedV << 0.5, 0, -1, 1.5, 2, 0.25, 1, -3, 1e-3, 0, 7, 1e300;
  MatrixXi expectedF(3, 3);
  expectedF << 0, 1, 2, 3, 2, 1, 3, 1, 0;
  const std::string ascii = headerFor("ascii") +
                            "1 2 0.5 0.25\n2 0\n"
                            "9 0.5 0 -1\n9 1.5 2 0.25\n9 1 -3 0.001\n"
                            "9 0 7\n1e300\n"        // values may wrap to the next line
                            "0 3 0 1 2\n1 4 3 2 1 0\n";
  MatrixXd V;
  MatrixXi F;
  readOrFail(writeFile("types.ply", ascii), V, F);
  CHECK(V == expectedV);
  CHECK(F == expectedF);
  for (const bool bigEndian : {false, true}) {
    ByteWriter w{bigEndian, headerFor(bigEndian ? "binary_big_endian" : "binary_little_endian")};
    w.put<std::uint8_t>(1); w.put<std::uint8_t>(2); w.put<float>(0.5f); w.put<float>(0.25f);
    w.put<std::uint8_t>(2); w.put<std::uint8_t>(0);
    for (Index i = 0; i < 4; ++i) {
      w.put<std::uint8_t>(9);
      w.put<float>(float(expectedV(i, 0)));
      w.put<std::int16_t>(std::int16_t(expectedV(i, 1)));
      w.put<double>(expectedV(i, 2));
    }
    w.put<std::int32_t>(0); w.put<std::uint16_t>(3);
    for (std::uint32_t i : {0u, 1u, 2u}) w.put<std::uint32_t>(i);
    w.put<std::int32_t>(1); w.put<std::uint16_t>(4);
    for (std::uint32_t i : {3u, 2u, 1u, 0u}) w.put<std::uint32_t>(i);
    INFO("big endian: " << bigEndian);
    readOrFail(writeFile(bigEndian ? "types_be.ply.gz" : "types_le.ply", w.bytes, bigEndian), V, F);
    CHECK(V == expectedV);
    CHECK(F == expectedF);
  }
}

TEST_CASE("readers: malformed files give false and a message naming file, place and problem") {
  // OBJ
  expectReadFailure(writeFile("e1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"), {"line 4", "out of range"});
  expectReadFailure(writeFile("e2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"), {"line 4", "reference 0"});
  expectReadFailure(writeFile("e3.obj", "v 0 0 0\nv nan 0 0\n"), {"line 2", "non-finite"});
  expectReadFailure(writeFile("e4.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2/3/4 2 3\n"), {"line 4", "malformed face corner"});
  expectReadFailure(writeFile("e5.obj", "v 0 0 0\nv 1 0 0\n# comment\nf 1 2\n"), {"line 4", "2 corners"});
  expectReadFailure(writeFile("e6.obj", "v 0 0\n"), {"line 1", "three coordinates"});
  expectReadFailure(writeFile("e7.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n"), {"line 4", "out of range"});
  // nothing an OBJ reader knows (another format under .obj, text): not an empty mesh
  expectReadFailure(writeFile("e8.obj", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), {"no vertex record"});
  expectReadFailure(writeFile("e9.obj", "hello\nworld\n"), {"no vertex record"});
  // OFF (through the existing reader)
  expectReadFailure(writeFile("e1.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"), {"line 6", "out of range"});
  expectReadFailure(writeFile("e2.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"), {"file ends"});
  expectReadFailure(writeFile("e3.off", "OFF\n3 1 -5\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), {"line 2", "negative edge count"});
  // PLY header
  const std::string vertexHeader = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string faceHeader = "element face 1\nproperty list uchar int vertex_indices\n";
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  expectReadFailure(writeFile("h1.ply", "plx\n"), {"line 1", "not a PLY"});
  expectReadFailure(writeFile("h2.ply", "ply\nformat ascii 1.0\n" + vertexHeader), {"no end_header"});
  expectReadFailure(writeFile("h3.ply", "ply\nformat utf8 1.0\n"), {"line 2", "unknown format"});
  expectReadFailure(writeFile("h4.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty quad x\n"), {"line 4", "unknown property type"});
  expectReadFailure(writeFile("h5.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nend_header\n"),
                    {"no 'z' property"});
  expectReadFailure(writeFile("h6.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nproperty float y\n"
                                        "property float z\nend_header\n0 0 0\n"),
                    {"does not fit"});
  expectReadFailure(writeFile("h7.ply", "ply\nformat ascii 1.0\nelement vertex -3\n"), {"line 3", "count"});
  expectReadFailure(writeFile("h8.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\n"),
                    {"line 4", "floating-point count"});
  // PLY body, ascii: the line of the problem
  expectReadFailure(writeFile("a1.ply", "ply\nformat ascii 1.0\n" + vertexHeader + faceHeader + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"),
                    {"line 13", "not an integer in [0, 3)"});
  expectReadFailure(writeFile("a2.ply", "ply\nformat ascii 1.0\n" + vertexHeader + faceHeader + "end_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
                    {"line 11", "non-finite"});
  expectReadFailure(writeFile("a3.ply", "ply\nformat ascii 1.0\n" + vertexHeader + faceHeader + "end_header\n0 0 0\n1 0 0\n0 1 0\n"),
                    {"truncated"});
  expectReadFailure(writeFile("a4.ply", "ply\nformat ascii 1.0\n" + vertexHeader + faceHeader + "end_header\n" + body + "0 0 0\n"),
                    {"line 14", "more data than the header declares"});
  expectReadFailure(writeFile("a5.ply", "ply\nformat ascii 1.0\n" + vertexHeader + faceHeader + "end_header\n0 0 0\n1 0 0\n0 1 x\n3 0 1 2\n"),
                    {"line 12", "'x' is not a number"});
  expectReadFailure(writeFile("a6.ply", "ply\nformat ascii 1.0\n" + vertexHeader + faceHeader + "end_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
                    {"line 13", "2 corners"});
  // A header that lies about a huge count: fails at the end of the data, without a huge allocation.
  {
    const std::string lie = "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
                            "property float y\nproperty float z\nend_header\n";
    expectReadFailure(writeFile("a7.ply", lie + "0123456789ab"),
                      {"byte " + std::to_string(lie.size() + 12), "vertex 1", "truncated"});
  }
  expectReadFailure(writeFile("a8.ply", "ply\nformat ascii 1.0\nelement junk 999999999999999999\nproperty uchar a\nend_header\n1 2 3\n"),
                    {"truncated"});
  // PLY body, binary: the byte offset of the problem
  {
    const std::string h = "ply\nformat binary_little_endian 1.0\n" + vertexHeader + faceHeader + "end_header\n";
    ByteWriter w{false, h};
    for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) w.put(x);
    w.put<std::uint8_t>(3);
    w.put<std::int32_t>(0);
    w.put<std::int32_t>(1);
    w.put<std::int32_t>(-1);
    const std::string badIndexOffset = std::to_string(h.size() + 36 + 1 + 8);
    expectReadFailure(writeFile("b1.ply", w.bytes), {"byte " + badIndexOffset, "vertex index -1"});
    expectReadFailure(writeFile("b2.ply.gz", w.bytes.substr(0, h.size() + 30), true),
                      {"byte " + std::to_string(h.size() + 28), "truncated"});
    std::string nan = w.bytes;
    const float quietNaN = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&nan[h.size() + 16], &quietNaN, 4);
    expectReadFailure(writeFile("b3.ply", nan), {"byte " + std::to_string(h.size() + 16), "non-finite"});
    expectReadFailure(writeFile("b4.ply", w.bytes.substr(0, w.bytes.size() - 4) + std::string("\0\0\0\0\0", 5)),
                      {"byte " + std::to_string(w.bytes.size()), "more data"});
  }
  // A corrupt gzip stream is a read error, not a crash.
  {
    const std::string plain = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    writeFile("c1.off.gz", plain, true);
    std::string bytes;
    {
      std::ifstream in(scratchPath("c1.off.gz"), std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    bytes[bytes.size() - 6] ^= 0x55; // the CRC
    expectReadFailure(writeFile("c2.off.gz", bytes), {"readOFF"});
  }
}

TEST_CASE("readPLY: ascii values must fit their declared property type") {
  // An ascii value that the declared type cannot hold (that a binary file of the same header could
  // not store) is refused with the line and the type, not wrapped or widened to a double.
  auto ply = [](const std::string& header, const std::string& body) {
    return "ply\nformat ascii 1.0\n" + header + "end_header\n" + body;
  };
  auto bodyLine = [](const std::string& header, int k) { // "line N" of the k-th body line (0-based)
    return "line " + std::to_string(2 + std::count(header.begin(), header.end(), '\n') + 2 + k);
  };
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string vertices = "element vertex 3\n" + xyz;
  const std::string triangle = "0 0 0\n1 0 0\n0 1 0\n";
  const std::string ucharFace = "element face 1\nproperty list uchar int vertex_indices\n";
  // list counts: beyond the count type (also in an element that is only skipped), negative
  {
    const std::string h = vertices + ucharFace + "element extra 1\nproperty list uchar int values\n";
    std::string values = "256";
    for (int k = 0; k < 256; ++k) values += " 0";
    expectReadFailure(writeFile("t1.ply", ply(h, triangle + "3 0 1 2\n" + values + "\n")),
                      {bodyLine(h, 4), "extra 0", "'256'", "uchar"});
  }
  expectReadFailure(writeFile("t2.ply", ply(vertices + ucharFace, triangle + "300 0 1 2\n")),
                    {bodyLine(vertices + ucharFace, 3), "face 0", "'300'", "uchar"});
  expectReadFailure(writeFile("t3.ply", ply(vertices + ucharFace, triangle + "-3 0 1 2\n")),
                    {bodyLine(vertices + ucharFace, 3), "face 0", "'-3'", "uchar"});
  {
    const std::string h = vertices + "element face 1\nproperty list char int vertex_indices\n";
    expectReadFailure(writeFile("t4.ply", ply(h, triangle + "-1 0 1 2\n")), {bodyLine(h, 3), "not a non-negative integer"});
  }
  // vertex indices: beyond the index type even where the mesh has that many vertices, overflowing int
  {
    std::string many;
    for (int k = 0; k < 300; ++k) many += std::to_string(k) + " 0 0\n";
    const std::string h = "element vertex 300\n" + xyz + "element face 1\nproperty list uchar uchar vertex_indices\n";
    expectReadFailure(writeFile("t5.ply", ply(h, many + "3 0 1 256\n")), {bodyLine(h, 300), "face 0", "'256'", "uchar"});
  }
  expectReadFailure(writeFile("t6.ply", ply(vertices + ucharFace, triangle + "3 0 1 2147483648\n")),
                    {bodyLine(vertices + ucharFace, 3), "'2147483648'", "int"});
  expectReadFailure(writeFile("t7.ply", ply(vertices + ucharFace, triangle + "3 0 1 -1\n")),
                    {bodyLine(vertices + ucharFace, 3), "vertex index -1"});
  // scalars: a fraction, or out of range, in an integer property (read or skipped); beyond float
  {
    const std::string h = "element vertex 3\nproperty int x\nproperty float y\nproperty float z\n" + ucharFace;
    expectReadFailure(writeFile("t8.ply", ply(h, "0 0 0\n0.5 0 0\n0 1 0\n3 0 1 2\n")), {bodyLine(h, 1), "'0.5'", "int"});
  }
  {
    const std::string h = "element vertex 3\n" + xyz + "property uchar red\nproperty short level\n" + ucharFace;
    expectReadFailure(writeFile("t9.ply", ply(h, "0 0 0 1.5 0\n1 0 0 0 0\n0 1 0 0 0\n3 0 1 2\n")),
                      {bodyLine(h, 0), "vertex 0", "'1.5'", "uchar"});
    expectReadFailure(writeFile("t10.ply", ply(h, "0 0 0 0 0\n1 0 0 0 40000\n0 1 0 0 0\n3 0 1 2\n")),
                      {bodyLine(h, 1), "vertex 1", "'40000'", "short"});
    expectReadFailure(writeFile("t11.ply", ply(h, "0 0 0 0 0\n1 0 0 0 0\n0 1 0 nan 0\n3 0 1 2\n")),
                      {bodyLine(h, 2), "vertex 2", "'nan'", "uchar"});
  }
  expectReadFailure(writeFile("t12.ply", ply(vertices + ucharFace, "0 0 0\n1 0 1e39\n0 1 0\n3 0 1 2\n")),
                    {bodyLine(vertices + ucharFace, 1), "'1e39'", "float"});
  // the limits of each type are accepted
  {
    const std::string h = "element vertex 3\n" + xyz +
                          "property char a\nproperty uchar b\nproperty short c\nproperty ushort d\nproperty int e\n"
                          "property uint f\nproperty double g\n" + ucharFace;
    const std::string limits = " -128 255 -32768 65535 -2147483648 4294967295 1e300\n";
    MatrixXd V;
    MatrixXi F;
    readOrFail(writeFile("t13.ply", ply(h, "0 0 3.4028235e38" + limits + "1 0 -3.4028235e38 127 0 32767 0 2147483647 0 -1e300\n"
                                           "0 1 1e-50 0 0 0 0 0 0 0\n3 0 1 2\n")),
               V, F);
    CHECK(V(0, 2) == 3.4028235e38); // (read as written: float range, double value)
    CHECK(F.rows() == 1);
  }
}

TEST_CASE("writeMesh: bad input and bad paths give false and a message") {
  MatrixXd V;
  MatrixXi F;
  testMesh(V, F);
  std::string error;
  CHECK_FALSE(Eigen::writeMesh(scratchPath("x.stl"), V, F, &error));
  CHECK(error.find("unknown mesh format") != std::string::npos);
  CHECK_FALSE(Eigen::writeMesh(scratchPath("x.obj"), V, F, &error, true));
  CHECK(error.find("only available for PLY") != std::string::npos);
  MatrixXd badV = V;
  badV(5, 1) = std::numeric_limits<double>::infinity();
  CHECK_FALSE(Eigen::writeMesh(scratchPath("x.off"), badV, F, &error));
  CHECK(error.find("vertex 5") != std::string::npos);
  MatrixXi badF = F;
  badF(7, 2) = int(V.rows());
  CHECK_FALSE(Eigen::writeMesh(scratchPath("x.ply"), V, badF, &error));
  CHECK(error.find("face 7") != std::string::npos);
  CHECK_FALSE(Eigen::writeMesh(scratchPath("no/such/folder/x.ply"), V, F, &error));
  CHECK(error.find("cannot create") != std::string::npos);
  CHECK(error.find("no/such/folder/x.ply") != std::string::npos);
}

TEST_CASE("readers: fuzzed files never crash; success means a valid mesh, failure a message") {
  MatrixXd V;
  MatrixXi F;
  Eigen::icosphereMesh(0, V, F);
  V *= 0.7;
  struct Base {
    std::string name, bytes;
  };
  std::vector<Base> bases;
  for (const auto& format : {std::make_pair(std::string("off"), false), std::make_pair(std::string("obj"), false),
                             std::make_pair(std::string("ply"), false), std::make_pair(std::string("ply"), true)}) {
    const std::string path = scratchPath(std::string("base") + (format.second ? "_bin." : ".") + format.first);
    REQUIRE(Eigen::writeMesh(path, V, F, nullptr, format.second));
    std::ifstream in(path, std::ios::binary);
    bases.push_back({std::string("fuzz") + (format.second ? "_bin." : ".") + format.first,
                     std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>())});
  }
  {
    // A big-endian PLY with polygons, uchar colours and an extra element, as a further base.
    const std::string h = "ply\nformat binary_big_endian 1.0\nelement vertex 5\nproperty short x\nproperty float y\n"
                          "property double z\nproperty uchar red\nelement face 2\nproperty list uint ushort vertex_indices\n"
                          "element edge 1\nproperty list uchar int vertex_pair\nend_header\n";
    ByteWriter w{true, h};
    for (int i = 0; i < 5; ++i) {
      w.put<std::int16_t>(std::int16_t(i));
      w.put<float>(0.5f * float(i * i));
      w.put<double>(-1.0 * i);
      w.put<std::uint8_t>(200);
    }
    w.put<std::uint32_t>(4);
    for (std::uint16_t i : {0, 1, 2, 3}) w.put(i);
    w.put<std::uint32_t>(3);
    for (std::uint16_t i : {3, 2, 4}) w.put(i);
    w.put<std::uint8_t>(2);
    w.put<std::int32_t>(0);
    w.put<std::int32_t>(4);
    bases.push_back({"fuzz_be.ply", w.bytes});
  }
  for (const Base& base : bases) { // every base reads as it is
    MatrixXd V2;
    MatrixXi F2;
    readOrFail(writeFile(base.name, base.bytes), V2, F2);
    CHECK(F2.rows() > 0);
  }

  const char* roundsText = std::getenv("UC_MESH_FUZZ_ROUNDS");
  const int rounds = roundsText ? std::max(1, std::atoi(roundsText)) : 700;
  std::mt19937 generator(20240521u);
  auto uniform = [&](std::size_t n) { return std::size_t(std::uniform_int_distribution<std::size_t>(0, n - 1)(generator)); };
  const char* const numbers[] = {"0", "1", "-1", "2", "3", "255", "256", "65535", "2147483647", "2147483648",
                                 "4294967295", "99999999999999999999", "1e9", "nan", "inf", "-0", "0.5"};
  int successes = 0, failures = 0;
  for (int round = 0; round < rounds; ++round)
    for (const Base& base : bases) {
      std::string bytes = base.bytes;
      const int mutations = 1 + int(uniform(4));
      for (int m = 0; m < mutations && !bytes.empty(); ++m) {
        switch (uniform(5)) {
          case 0: // random byte flips
            for (std::size_t k = 1 + uniform(3); k > 0; --k) bytes[uniform(bytes.size())] ^= char(1 + uniform(255));
            break;
          case 1: // truncation
            bytes.resize(uniform(bytes.size()));
            break;
          case 2: { // insertion of random bytes or text
            std::string inserted;
            for (std::size_t k = 1 + uniform(8); k > 0; --k)
              inserted += uniform(2) ? char(uniform(256)) : " 0123456789-./\nvf#"[uniform(18)];
            bytes.insert(uniform(bytes.size() + 1), inserted);
            break;
          }
          case 3: { // a number (mostly in the header) replaced by another
            const std::size_t limit = std::min<std::size_t>(bytes.size(), uniform(2) ? 400 : bytes.size());
            std::vector<std::size_t> starts;
            for (std::size_t i = 0; i < limit; ++i)
              if (std::isdigit(static_cast<unsigned char>(bytes[i])) && (i == 0 || !std::isdigit(static_cast<unsigned char>(bytes[i - 1]))))
                starts.push_back(i);
            if (starts.empty()) break;
            const std::size_t begin = starts[uniform(starts.size())];
            std::size_t end = begin;
            while (end < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[end]))) ++end;
            bytes.replace(begin, end - begin, numbers[uniform(sizeof(numbers) / sizeof(numbers[0]))]);
            break;
          }
          default: { // a line deleted or duplicated
            const std::size_t at = uniform(bytes.size());
            const std::size_t lineBegin = bytes.rfind('\n', at) == std::string::npos ? 0 : bytes.rfind('\n', at) + 1;
            std::size_t lineEnd = bytes.find('\n', at);
            lineEnd = lineEnd == std::string::npos ? bytes.size() : lineEnd + 1;
            if (uniform(2)) bytes.erase(lineBegin, lineEnd - lineBegin);
            else bytes.insert(lineEnd, bytes.substr(lineBegin, lineEnd - lineBegin));
          }
        }
      }
      const bool gzip = round % 5 >= 3;
      std::string path = writeFile(base.name + (gzip ? ".gz" : ""), bytes, gzip);
      if (round % 5 == 4) { // damage the compressed stream itself (header, deflate data or CRC)
        std::ifstream in(path, std::ios::binary);
        std::string compressed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        in.close();
        if (uniform(2)) compressed[uniform(compressed.size())] ^= char(1 + uniform(255));
        else compressed.resize(uniform(compressed.size()));
        path = writeFile(base.name + ".gz", compressed);
      }
      MatrixXd V2;
      MatrixXi F2;
      std::string error;
      if (Eigen::readMesh(path, V2, F2, &error)) {
        ++successes;
        REQUIRE(error.empty());
        REQUIRE(V2.cols() == 3);
        REQUIRE(F2.cols() == 3);
        REQUIRE(V2.allFinite());
        if (F2.rows() > 0) {
          REQUIRE(F2.minCoeff() >= 0);
          REQUIRE(F2.maxCoeff() < V2.rows());
        }
      } else {
        ++failures;
        INFO("round " << round << " base " << base.name);
        REQUIRE(!error.empty());
        REQUIRE(error.find(path) != std::string::npos);
      }
    }
  MESSAGE("fuzz: " << successes << " mutated files read, " << failures << " rejected");
  CHECK(successes > 0);
  CHECK(failures > 0);
}
