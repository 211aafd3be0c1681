// ReadMesh: reads a triangle mesh from an OFF, OBJ or PLY file (plain or gzip-compressed),
// choosing the reader by the file name's extension, or by the file's first bytes when the
// extension names no format (e.g. "mesh.gz").

#ifndef EIGEN_MESHTOOLS_READMESH_H
#define EIGEN_MESHTOOLS_READMESH_H

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal The mesh formats the readers and writers know. */
enum class MeshFormat { Unknown, OFF, OBJ, PLY };

/** \internal The format named by the extension of \a path (case-insensitive), after dropping a
  * trailing ".gz"; \a compressed tells whether there was one. */
inline MeshFormat meshFormatFromExtension(const std::string& path, bool& compressed)
{
  std::string lower(path);
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  compressed = lower.size() >= 3 && lower.compare(lower.size() - 3, 3, ".gz") == 0;
  if (compressed) lower.erase(lower.size() - 3);
  const std::string::size_type dot = lower.find_last_of("./\\");
  if (dot == std::string::npos || lower[dot] != '.') return MeshFormat::Unknown;
  const std::string extension = lower.substr(dot + 1);
  if (extension == "off") return MeshFormat::OFF;
  if (extension == "obj") return MeshFormat::OBJ;
  if (extension == "ply") return MeshFormat::PLY;
  return MeshFormat::Unknown;
}

/** \internal Guesses the format from the first (decompressed) bytes of the file at \a path:
  * "ply" starts PLY, an OFF keyword starts OFF, an OBJ record keyword or a '#' comment starts OBJ. */
inline MeshFormat meshFormatFromContent(const std::string& path)
{
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file) return MeshFormat::Unknown;
  char head[64] = {0};
  const int got = gzread(file, head, sizeof(head) - 1);
  gzclose(file);
  if (got <= 0) return MeshFormat::Unknown;
  const char* p = head;
  while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
  const char* end = p;
  while (*end && !std::isspace(static_cast<unsigned char>(*end))) ++end;
  const std::string first(p, end);
  if (first == "ply") return MeshFormat::PLY;
  if (first == "OFF" || first == "COFF" || first == "NOFF" || first == "CNOFF" || first == "STOFF") return MeshFormat::OFF;
  static const char* const objKeywords[] = {"v", "vt", "vn", "f", "o", "g", "s", "mtllib", "usemtl"};
  for (const char* keyword : objKeywords)
    if (first == keyword) return MeshFormat::OBJ;
  if (!first.empty() && first[0] == '#') return MeshFormat::OBJ;
  return MeshFormat::Unknown;
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Reads a triangle mesh from an OFF, OBJ or PLY file, plain or gzip-compressed.
  *
  * The format follows the extension (case-insensitive, after an optional ".gz"): \c .off ->
  * readOFF(), \c .obj -> readOBJ(), \c .ply -> readPLY() (ascii or binary). Any file may be gzip
  * compressed whatever its name. If the extension names none of these (e.g. "mesh.gz"), the first
  * bytes decide: \c ply, an OFF keyword, or an OBJ record / '#' comment.
  *
  * \param path   file to read.
  * \param V      on success, the #V x 3 vertex positions.
  * \param F      on success, the #F x 3 triangles (0-based; polygons fan-triangulated).
  * \param error  if not null, receives a message naming the file and the line (or byte offset in
  *               a binary PLY body) when reading fails, and is cleared on success.
  * \returns true on success; on failure \a V and \a F are left unchanged.
  *
  * \sa writeMesh(), readOFF(), readOBJ(), readPLY()
  */
inline bool readMesh(const std::string& path, MatrixXd& V, MatrixXi& F, std::string* error = nullptr)
{
  using internal::meshtools::MeshFormat;
  bool compressed = false;
  MeshFormat format = internal::meshtools::meshFormatFromExtension(path, compressed);
  if (format == MeshFormat::Unknown) format = internal::meshtools::meshFormatFromContent(path);
  switch (format)
  {
    case MeshFormat::OFF: return readOFF(path, V, F, error);
    case MeshFormat::OBJ: return readOBJ(path, V, F, error);
    case MeshFormat::PLY: return readPLY(path, V, F, error);
    default: break;
  }
  const internal::OffLineReader probe(path);
  if (!probe.isOpen()) return internal::meshFileFailure(error, "readMesh", path, "", "cannot open file (" + probe.openError() + ")");
  return internal::meshFileFailure(error, "readMesh", path, "",
                                   "unknown mesh format (the extension is not .off, .obj or .ply, optionally "
                                   "followed by .gz, and the content starts like none of them)");
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_READMESH_H
