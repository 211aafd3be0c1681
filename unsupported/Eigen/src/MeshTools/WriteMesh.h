// WriteMesh: writes a triangle mesh as OFF, OBJ (ascii) or PLY (ascii or binary little-endian),
// chosen by the file name's extension; a trailing ".gz" gzip-compresses the file. Coordinates are
// written with 17 significant digits (binary PLY: as doubles), so readMesh() gives back exactly
// the same V and F.

#ifndef EIGEN_MESHTOOLS_WRITEMESH_H
#define EIGEN_MESHTOOLS_WRITEMESH_H

#include <cstdio>

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal Buffered output to a gzip-compressed or plain file (zlib's transparent mode). */
class MeshOutput
{
public:
  MeshOutput(const std::string& path, bool compress) : m_file(nullptr), m_failed(false), m_openErrno(0)
  {
    errno = 0;
    m_file = gzopen(path.c_str(), compress ? "wb6" : "wbT");
    m_openErrno = errno;
  }
  ~MeshOutput() { close(); }
  MeshOutput(const MeshOutput&) = delete;
  MeshOutput& operator=(const MeshOutput&) = delete;

  /** \returns whether the file could be created. */
  bool isOpen() const { return m_file != nullptr; }

  /** \returns why creating the file failed (system message, or "out of memory" without errno). */
  std::string openError() const { return m_openErrno ? std::strerror(m_openErrno) : "out of memory"; }

  /** Appends \a count raw bytes. */
  void write(const void* bytes, std::size_t count)
  {
    m_buffer.append(static_cast<const char*>(bytes), count);
    if (m_buffer.size() >= (std::size_t(1) << 20)) flush();
  }
  /** Appends a string. */
  void write(const std::string& text) { write(text.data(), text.size()); }
  /** Appends a number with enough digits to read back the same double. */
  void writeNumber(double x)
  {
    char text[32];
    const int length = std::snprintf(text, sizeof(text), "%.17g", x);
    write(text, std::size_t(length));
  }
  /** Appends an integer. */
  void writeNumber(int i) { write(std::to_string(i)); }

  /** Flushes and closes the file. \returns false if any write or the close failed. */
  bool close()
  {
    if (!m_file) return false;
    flush();
    if (gzclose(m_file) != Z_OK) m_failed = true;
    m_file = nullptr;
    return !m_failed;
  }

private:
  void flush()
  {
    if (!m_buffer.empty() && gzwrite(m_file, m_buffer.data(), unsigned(m_buffer.size())) != int(m_buffer.size()))
      m_failed = true;
    m_buffer.clear();
  }

  gzFile m_file;
  bool m_failed;
  int m_openErrno;
  std::string m_buffer;
};

/** \internal Writes the body of an OFF file. */
inline void writeOffBody(MeshOutput& out, const MatrixXd& V, const MatrixXi& F)
{
  out.write("OFF\n" + std::to_string(V.rows()) + " " + std::to_string(F.rows()) + " 0\n");
  for (Index i = 0; i < V.rows(); ++i)
  {
    for (Index c = 0; c < 3; ++c)
    {
      out.writeNumber(c < V.cols() ? V(i, c) : 0.0);
      out.write(c < 2 ? " " : "\n", 1);
    }
  }
  for (Index f = 0; f < F.rows(); ++f)
  {
    out.write("3", 1);
    for (Index c = 0; c < 3; ++c)
    {
      out.write(" ", 1);
      out.writeNumber(F(f, c));
    }
    out.write("\n", 1);
  }
}

/** \internal Writes the body of an OBJ file (1-based references). */
inline void writeObjBody(MeshOutput& out, const MatrixXd& V, const MatrixXi& F)
{
  for (Index i = 0; i < V.rows(); ++i)
  {
    out.write("v", 1);
    for (Index c = 0; c < 3; ++c)
    {
      out.write(" ", 1);
      out.writeNumber(c < V.cols() ? V(i, c) : 0.0);
    }
    out.write("\n", 1);
  }
  for (Index f = 0; f < F.rows(); ++f)
  {
    out.write("f", 1);
    for (Index c = 0; c < 3; ++c)
    {
      out.write(" ", 1);
      out.writeNumber(F(f, c) + 1);
    }
    out.write("\n", 1);
  }
}

/** \internal Appends \a value in little-endian byte order. */
template <typename T>
void writeLittleEndian(MeshOutput& out, T value)
{
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  const std::uint16_t probe = 1;
  unsigned char firstByte;
  std::memcpy(&firstByte, &probe, 1);
  if (firstByte != 1) std::reverse(bytes, bytes + sizeof(T));
  out.write(bytes, sizeof(T));
}

/** \internal Writes a PLY file: double x, y, z and a uchar/int vertex_indices list. */
inline void writePlyBody(MeshOutput& out, const MatrixXd& V, const MatrixXi& F, bool binary)
{
  out.write(std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
            " 1.0\ncomment written by Eigen MeshTools\nelement vertex " + std::to_string(V.rows()) +
            "\nproperty double x\nproperty double y\nproperty double z\nelement face " + std::to_string(F.rows()) +
            "\nproperty list uchar int vertex_indices\nend_header\n");
  for (Index i = 0; i < V.rows(); ++i)
    for (Index c = 0; c < 3; ++c)
    {
      const double x = c < V.cols() ? V(i, c) : 0.0;
      if (binary) writeLittleEndian(out, x);
      else
      {
        out.writeNumber(x);
        out.write(c < 2 ? " " : "\n", 1);
      }
    }
  for (Index f = 0; f < F.rows(); ++f)
  {
    if (binary) writeLittleEndian(out, std::uint8_t(3));
    else out.write("3", 1);
    for (Index c = 0; c < 3; ++c)
    {
      if (binary) writeLittleEndian(out, std::int32_t(F(f, c)));
      else
      {
        out.write(" ", 1);
        out.writeNumber(F(f, c));
      }
    }
    if (!binary) out.write("\n", 1);
  }
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Writes a triangle mesh as OFF, OBJ or PLY, chosen by the extension, optionally gzip-compressed.
  *
  * The extension (case-insensitive, after an optional ".gz" which compresses the output) picks
  * the format: \c .off, \c .obj (1-based \c v / \c f records) or \c .ply (double x, y, z and a
  * uchar/int \c vertex_indices list; ascii, or binary little-endian when \a binary). Numbers are
  * written with 17 significant digits, so reading the file back with readMesh() gives exactly \a V
  * and \a F.
  *
  * \param path    file to create (overwritten if it exists).
  * \param V       #V x 3 (or #V x 2, then z = 0) finite vertex positions.
  * \param F       #F x 3 triangles, 0-based indices into the rows of V.
  * \param error   if not null, receives a message naming the file when writing fails, cleared on success.
  * \param binary  write binary PLY; only PLY has a binary form (true with .off or .obj fails).
  * \returns true on success; false on an unknown extension, invalid V or F (wrong column count,
  *          index out of range, non-finite coordinate) or an I/O error.
  *
  * \sa readMesh()
  */
inline bool writeMesh(const std::string& path, const MatrixXd& V, const MatrixXi& F, std::string* error = nullptr,
                      bool binary = false)
{
  using namespace internal::meshtools;
  auto fail = [&](const std::string& what) { return internal::meshFileFailure(error, "writeMesh", path, "", what); };
  bool compress = false;
  const MeshFormat format = meshFormatFromExtension(path, compress);
  if (format == MeshFormat::Unknown) return fail("unknown mesh format (use .off, .obj or .ply, optionally followed by .gz)");
  if (binary && format != MeshFormat::PLY) return fail("binary output is only available for PLY");
  if (V.rows() > 0 && V.cols() != 2 && V.cols() != 3) return fail("V must have 2 or 3 columns, it has " + std::to_string(V.cols()));
  for (Index i = 0; i < V.rows(); ++i)
    if (!V.row(i).allFinite()) return fail("vertex " + std::to_string(i) + " has a non-finite coordinate");
  std::string triangleError;
  if (!checkTriangles(F, V.rows(), "F", &triangleError)) return fail(triangleError);

  MeshOutput out(path, compress);
  if (!out.isOpen()) return fail("cannot create file (" + out.openError() + ")");
  if (format == MeshFormat::OFF) writeOffBody(out, V, F);
  else if (format == MeshFormat::OBJ) writeObjBody(out, V, F);
  else writePlyBody(out, V, F, binary);
  if (!out.close()) return fail("write error (disk full or file not writable?)");
  if (error) error->clear();
  return true;
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_WRITEMESH_H
