// ReadOFF: reads a triangle mesh from an ASCII OFF file, plain or gzip-compressed (zlib reads both).
//
// Input: a path. Output: vertex positions V (#V x 3) and triangles F (#F x 3, 0-based). Faces
// with more than three corners are fan-triangulated. Every malformed input (unreadable or corrupt
// file, bad header, missing or extra lines, indices out of range, non-finite coordinates) makes
// the reader return false with a message naming the file and the line; it never aborts.
// The line/byte reader, the message format and the final copy into V and F defined here are
// shared by the OBJ and PLY readers (ReadOBJ.h, ReadPLY.h).

#ifndef EIGEN_MESHTOOLS_READOFF_H
#define EIGEN_MESHTOOLS_READOFF_H

namespace Eigen {

namespace internal {

/** \internal Reader over a zlib stream (gzip or plain file) shared by the mesh readers: text
  * lines that skip blank lines and '#' comments (OFF, OBJ, PLY headers), then optionally raw
  * bytes (binary PLY bodies).
  *
  * Lines of up to maxLineLength characters are supported (a longer one is a read error, so that a
  * file without newlines cannot make the reader hold all of it as one string); the reader keeps
  * track of the current line number, and of the byte offset in binary mode, so that error messages
  * can point at the offending place. */
class OffLineReader
{
public:
  /** Longest line accepted (64 MiB). */
  static constexpr std::size_t maxLineLength = std::size_t(1) << 26;

  explicit OffLineReader(const std::string& path)
      : m_file(nullptr), m_line(0), m_openErrno(0), m_lineTooLong(false), m_binaryStart(-1), m_consumed(0),
        m_bufferPosition(0)
  {
    errno = 0;
    m_file = gzopen(path.c_str(), "rb");
    m_openErrno = errno;
    if (m_file) gzbuffer(m_file, 1 << 17);
  }
  ~OffLineReader() { if (m_file) gzclose(m_file); }
  OffLineReader(const OffLineReader&) = delete;
  OffLineReader& operator=(const OffLineReader&) = delete;

  /** \returns whether the file could be opened. */
  bool isOpen() const { return m_file != nullptr; }

  /** \returns why opening failed (system message, or "out of memory" when zlib gave no errno). */
  std::string openError() const { return m_openErrno ? std::strerror(m_openErrno) : "out of memory"; }

  /** \returns the number of the line returned by the last call to nextDataLine() (1-based). */
  long lineNumber() const { return m_line; }

  /** Reads the next line that holds data (comments stripped, not blank) into \a line.
    * \returns false at end of file or on a read error; then streamError() tells which. */
  bool nextDataLine(std::string& line)
  {
    while (readRawLine(line))
    {
      const std::string::size_type hash = line.find('#');
      if (hash != std::string::npos) line.erase(hash);
      if (line.find_first_not_of(" \t\r\n\f\v") != std::string::npos) return true;
    }
    return false;
  }

  /** \returns a description of a zlib or system read error, or an empty string at a clean end of file. */
  std::string streamError() const
  {
    if (m_lineTooLong) return "a line is longer than " + std::to_string(maxLineLength) + " characters";
    int code = Z_OK;
    const char* msg = gzerror(m_file, &code);
    if (code == Z_OK || code == Z_STREAM_END) return std::string();
    if (code == Z_ERRNO) return std::strerror(errno);
    return msg ? std::string(msg) : std::string("zlib error ") + std::to_string(code);
  }

  /** Reads the next \a count raw bytes into \a destination (binary mode: after the last line read,
    * no further lines may be read). \returns false if the stream ends first or on a read error
    * (then streamError() tells which). */
  bool readBytes(void* destination, std::size_t count)
  {
    if (m_binaryStart < 0)
    {
      m_binaryStart = static_cast<long long>(gztell(m_file));
      m_buffer.resize(std::size_t(1) << 16);
      m_bufferEnd = m_bufferPosition = 0;
    }
    unsigned char* out = static_cast<unsigned char*>(destination);
    while (count > 0)
    {
      if (m_bufferPosition == m_bufferEnd && !refill()) return false;
      const std::size_t take = std::min(count, m_bufferEnd - m_bufferPosition);
      std::memcpy(out, m_buffer.data() + m_bufferPosition, take);
      out += take;
      m_bufferPosition += take;
      m_consumed += take;
      count -= take;
    }
    return true;
  }

  /** \returns the byte offset in the (uncompressed) file of the next byte readBytes() returns. */
  long long byteOffset() const { return (m_binaryStart < 0 ? 0 : m_binaryStart) + static_cast<long long>(m_consumed); }

  /** \returns whether any byte is left after those read by readBytes(). */
  bool hasMoreBytes()
  {
    unsigned char probe;
    if (!readBytes(&probe, 1)) return false;
    --m_bufferPosition;
    --m_consumed;
    return true;
  }

private:
  bool readRawLine(std::string& line)
  {
    line.clear();
    char buffer[4096];
    bool gotAny = false;
    while (gzgets(m_file, buffer, sizeof(buffer)) != nullptr)
    {
      gotAny = true;
      line += buffer;
      if (!line.empty() && line.back() == '\n') break;
      if (line.size() > maxLineLength)
      {
        m_lineTooLong = true;
        ++m_line;
        return false;
      }
    }
    if (gotAny) ++m_line;
    return gotAny;
  }

  bool refill()
  {
    const int got = gzread(m_file, m_buffer.data(), unsigned(m_buffer.size()));
    if (got <= 0) return false;
    m_bufferPosition = 0;
    m_bufferEnd = std::size_t(got);
    return true;
  }

  gzFile m_file;
  long m_line;
  int m_openErrno;
  bool m_lineTooLong;
  long long m_binaryStart;        // uncompressed offset where binary reading began, -1 before
  std::size_t m_consumed;         // bytes returned by readBytes()
  std::vector<unsigned char> m_buffer;
  std::size_t m_bufferPosition, m_bufferEnd = 0;
};

/** \internal Parses a non-negative decimal integer token at \a p; advances \a p past it.
  * \returns false if there is no integer token or it does not fit into a long. */
inline bool offParseLong(const char*& p, long& value)
{
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(p, &end, 10);
  if (end == p || errno == ERANGE) return false;
  if (*end != '\0' && !std::isspace(static_cast<unsigned char>(*end))) return false;
  value = v;
  p = end;
  return true;
}

/** \internal Parses a floating-point token at \a p; advances \a p past it. */
inline bool offParseDouble(const char*& p, double& value)
{
  char* end = nullptr;
  const double v = std::strtod(p, &end);
  if (end == p) return false;
  if (*end != '\0' && !std::isspace(static_cast<unsigned char>(*end))) return false;
  value = v;
  p = end;
  return true;
}

/** \internal \returns whether only white space remains at \a p. */
inline bool offOnlySpaceLeft(const char* p)
{
  while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
  return *p == '\0';
}

/** \internal Sets \a error (if not null) to "<who>: '<path>' <where>: <what>" (without
  * " <where>" when it is empty) and \returns false: the message format of every mesh reader and
  * writer. */
inline bool meshFileFailure(std::string* error, const char* who, const std::string& path, const std::string& where,
                            const std::string& what)
{
  if (error) *error = std::string(who) + ": '" + path + "'" + (where.empty() ? "" : " " + where) + ": " + what;
  return false;
}

/** \internal The end of every mesh reader: checks that the stream ended cleanly and that the
  * triangles fit into int, then copies the row-major \a coords and \a tris into V and F and clears
  * \a error. \returns true, or what \a fail returns for the problem found. */
template <typename Fail>
bool meshReadFinish(const OffLineReader& reader, const std::vector<double>& coords, const std::vector<int>& tris,
                    MatrixXd& V, MatrixXi& F, std::string* error, Fail fail)
{
  const std::string streamError = reader.streamError();
  if (!streamError.empty()) return fail("read error after the last record (" + streamError + ")");
  if (tris.size() / 3 > std::size_t(std::numeric_limits<int>::max())) return fail("too many triangles after triangulation");
  V = Map<const Matrix<double, Dynamic, 3, RowMajor>>(coords.data(), Index(coords.size() / 3), 3);
  F = Map<const Matrix<int, Dynamic, 3, RowMajor>>(tris.data(), Index(tris.size() / 3), 3);
  if (error) error->clear();
  return true;
}

} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Reads a triangle mesh from an OFF file, plain or gzip-compressed.
  *
  * The header keyword may be \c OFF, \c COFF, \c NOFF, \c CNOFF or \c STOFF (extra per-vertex values
  * such as colours, normals or texture coordinates are ignored), optionally followed on the same
  * line by the counts <tt>\#vertices \#faces [\#edges]</tt>. Comments start with '#'. Each face line
  * is <tt>k i_1 ... i_k [colour]</tt> with 0-based indices and k >= 3; a face with k > 3 corners is
  * split into the fan (i_1, i_j, i_{j+1}). Binary OFF is not supported.
  *
  * \param path   file to read; gzip-compressed and plain files are both accepted.
  * \param V      on success, the #V x 3 vertex positions.
  * \param F      on success, the #F x 3 triangles (0-based vertex indices, file orientation kept).
  * \param error  if not null, receives a message naming the file and line when reading fails,
  *               and is cleared on success.
  * \returns true on success. On failure \a V and \a F are left unchanged.
  */
inline bool readOFF(const std::string& path, Eigen::MatrixXd& V, Eigen::MatrixXi& F,
                    std::string* error = nullptr)
{
  internal::OffLineReader reader(path);
  std::string line;
  long vertexCount = -1, faceCount = -1;

  auto fail = [&](const std::string& what) {
    if (error)
    {
      *error = "readOFF: '" + path + "'";
      if (reader.isOpen() && reader.lineNumber() > 0) *error += " line " + std::to_string(reader.lineNumber());
      *error += ": " + what;
    }
    return false;
  };
  auto endOfInput = [&](const std::string& expected) {
    const std::string streamError = reader.streamError();
    if (!streamError.empty()) return fail("read error (" + streamError + ") while reading " + expected);
    return fail("file ends before " + expected);
  };

  if (!reader.isOpen())
    return fail("cannot open file (" + reader.openError() + ")");

  try
  {
    // ---- header keyword, optionally followed by the counts ---------------------------------
    if (!reader.nextDataLine(line)) return endOfInput("the OFF header");
    const char* p = line.c_str();
    while (std::isspace(static_cast<unsigned char>(*p))) ++p;
    const char* keywordBegin = p;
    while (*p && !std::isspace(static_cast<unsigned char>(*p))) ++p;
    const std::string keyword(keywordBegin, p);
    if (keyword != "OFF" && keyword != "COFF" && keyword != "NOFF" && keyword != "CNOFF" && keyword != "STOFF")
      return fail("not an OFF file (header keyword is '" + keyword.substr(0, 32) +
                  "'; expected OFF, COFF, NOFF, CNOFF or STOFF)");
    if (line.find("BINARY") != std::string::npos) return fail("binary OFF is not supported");

    // ---- counts: #vertices #faces [#edges] ---------------------------------------------------
    if (internal::offOnlySpaceLeft(p))
    {
      if (!reader.nextDataLine(line)) return endOfInput("the vertex and face counts");
      p = line.c_str();
    }
    long edgeCount = 0;
    if (!internal::offParseLong(p, vertexCount) || !internal::offParseLong(p, faceCount))
      return fail("expected '#vertices #faces #edges' after the header");
    if (!internal::offOnlySpaceLeft(p) && (!internal::offParseLong(p, edgeCount) || !internal::offOnlySpaceLeft(p)))
      return fail("unexpected text after '#vertices #faces #edges'");
    if (edgeCount < 0) return fail("negative edge count " + std::to_string(edgeCount));
    if (vertexCount < 0 || faceCount < 0)
      return fail("negative vertex or face count (" + std::to_string(vertexCount) + ", " +
                  std::to_string(faceCount) + ")");
    if (vertexCount > std::numeric_limits<int>::max() || faceCount > std::numeric_limits<int>::max())
      return fail("vertex or face count does not fit into int");

    // Grow as lines arrive rather than trusting the header for one huge allocation.
    const std::size_t reserveCap = std::size_t(1) << 20;

    // ---- vertices ----------------------------------------------------------------------------
    std::vector<double> coords;
    coords.reserve(3 * std::min<std::size_t>(std::size_t(vertexCount), reserveCap));
    for (long v = 0; v < vertexCount; ++v)
    {
      if (!reader.nextDataLine(line))
        return endOfInput("all vertices were read (got " + std::to_string(v) + " of " +
                          std::to_string(vertexCount) + ")");
      p = line.c_str();
      for (int c = 0; c < 3; ++c)
      {
        double x;
        if (!internal::offParseDouble(p, x))
          return fail("vertex " + std::to_string(v) + ": expected three coordinates");
        if (!std::isfinite(x)) return fail("vertex " + std::to_string(v) + " has a non-finite coordinate");
        coords.push_back(x);
      }
    }

    // ---- faces (fan-triangulated) ------------------------------------------------------------
    std::vector<int> tris;
    tris.reserve(3 * std::min<std::size_t>(std::size_t(faceCount), reserveCap));
    std::vector<int> corners;
    for (long f = 0; f < faceCount; ++f)
    {
      if (!reader.nextDataLine(line))
        return endOfInput("all faces were read (got " + std::to_string(f) + " of " + std::to_string(faceCount) + ")");
      p = line.c_str();
      long k;
      if (!internal::offParseLong(p, k)) return fail("face " + std::to_string(f) + ": expected the corner count");
      if (k < 3) return fail("face " + std::to_string(f) + " has " + std::to_string(k) + " corners (need at least 3)");
      if (k > vertexCount)
        return fail("face " + std::to_string(f) + " has more corners (" + std::to_string(k) + ") than the mesh has vertices");
      corners.clear();
      for (long c = 0; c < k; ++c)
      {
        long index;
        if (!internal::offParseLong(p, index))
          return fail("face " + std::to_string(f) + ": expected " + std::to_string(k) + " vertex indices");
        if (index < 0 || index >= vertexCount)
          return fail("face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                      " out of range [0, " + std::to_string(vertexCount) + ")");
        corners.push_back(int(index));
      }
      // Anything left on the line is a face colour, which is ignored.
      for (long c = 1; c + 1 < k; ++c)
      {
        tris.push_back(corners[0]);
        tris.push_back(corners[std::size_t(c)]);
        tris.push_back(corners[std::size_t(c + 1)]);
      }
    }

    // ---- nothing may follow the declared faces -----------------------------------------------
    if (reader.nextDataLine(line))
      return fail("more data than the header declares (" + std::to_string(vertexCount) + " vertices, " +
                  std::to_string(faceCount) + " faces)");
    return internal::meshReadFinish(reader, coords, tris, V, F, error, fail);
  }
  catch (const std::bad_alloc&)
  {
    return fail("out of memory");
  }
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_READOFF_H
