// ReadPLY: reads the triangles of a PLY file (Stanford polygon format: ascii, binary_little_endian
// or binary_big_endian), plain or gzip-compressed (zlib reads both). Vertex x, y, z of any
// property type, the face index list of any count/index type, polygons fan-triangulated, other
// properties and elements skipped. Malformed input (an ascii value its declared type cannot hold
// included) makes it return false with a message naming the file and the line (ascii, header) or
// byte offset (binary body); it never aborts, and header counts are never trusted for large
// allocations.

#ifndef EIGEN_MESHTOOLS_READPLY_H
#define EIGEN_MESHTOOLS_READPLY_H

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal The scalar types of PLY properties. */
enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64, Invalid };

/** \internal \returns the classic name of \a type ("uchar", "int", "float", ...), or with \a sized
  * its sized name ("uint8", "int32", "float32", ...). */
inline const char* plyTypeName(PlyType type, bool sized = false)
{
  static const char* const names[][2] = {{"char", "int8"},   {"uchar", "uint8"}, {"short", "int16"},
                                         {"ushort", "uint16"}, {"int", "int32"},   {"uint", "uint32"},
                                         {"float", "float32"}, {"double", "float64"}};
  return type == PlyType::Invalid ? "?" : names[int(type)][sized ? 1 : 0];
}

/** \internal \returns the type named \a name (both the classic and the sized spellings), or Invalid. */
inline PlyType plyTypeFromName(const std::string& name)
{
  for (int t = 0; t < 8; ++t)
    if (name == plyTypeName(PlyType(t)) || name == plyTypeName(PlyType(t), true)) return PlyType(t);
  return PlyType::Invalid;
}

/** \internal The smallest and largest value of each integer PLY type (char ... uint). */
inline double plyIntegerLimit(PlyType type, bool highest)
{
  static const double limits[][2] = {{-128.0, 127.0}, {0.0, 255.0}, {-32768.0, 32767.0},
                                     {0.0, 65535.0}, {-2147483648.0, 2147483647.0}, {0.0, 4294967295.0}};
  return limits[int(type)][highest ? 1 : 0];
}

/** \internal \returns whether a binary value of type \a type can hold \a value (read from ascii):
  * an integer in the type's range for the integer types; for float, a value that does not round
  * to infinity (NaN and infinities themselves fit both floating-point types). */
inline bool plyValueFits(PlyType type, double value)
{
  if (type == PlyType::Float64) return true;
  if (type == PlyType::Float32) // from 2^128 - 2^103 on, a double rounds to float's infinity
    return !std::isfinite(value) || std::abs(value) < std::ldexp(2.0 - std::ldexp(1.0, -24), 127);
  return value == std::floor(value) && value >= plyIntegerLimit(type, false) && value <= plyIntegerLimit(type, true);
}

/** \internal \returns what a value of the integer or float type \a type may be, for messages. */
inline std::string plyTypeRange(PlyType type)
{
  if (type == PlyType::Float32) return "magnitudes up to 3.4028235e38";
  return "an integer in [" + std::to_string((long long)plyIntegerLimit(type, false)) + ", " +
         std::to_string((long long)plyIntegerLimit(type, true)) + "]";
}

/** \internal \returns the size in bytes of a binary value of type \a type. */
inline std::size_t plyTypeSize(PlyType type)
{
  static const std::size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8, 0};
  return sizes[int(type)];
}

/** \internal Decodes one binary value of type \a type from \a bytes, reversing the byte order
  * first if \a swap. */
inline double plyDecode(unsigned char* bytes, PlyType type, bool swap)
{
  const std::size_t size = (std::min)(plyTypeSize(type), std::size_t(8));  // (the bound tells GCC's
  if (swap) std::reverse(bytes, bytes + size);                               // overflow check too)
  switch (type)
  {
    case PlyType::Int8: { std::int8_t v; std::memcpy(&v, bytes, 1); return double(v); }
    case PlyType::UInt8: { std::uint8_t v; std::memcpy(&v, bytes, 1); return double(v); }
    case PlyType::Int16: { std::int16_t v; std::memcpy(&v, bytes, 2); return double(v); }
    case PlyType::UInt16: { std::uint16_t v; std::memcpy(&v, bytes, 2); return double(v); }
    case PlyType::Int32: { std::int32_t v; std::memcpy(&v, bytes, 4); return double(v); }
    case PlyType::UInt32: { std::uint32_t v; std::memcpy(&v, bytes, 4); return double(v); }
    case PlyType::Float32: { float v; std::memcpy(&v, bytes, 4); return double(v); }
    case PlyType::Float64: { double v; std::memcpy(&v, bytes, 8); return v; }
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

/** \internal One property of a PLY element: a scalar, or a list (count type + item type). */
struct PlyProperty
{
  std::string name;
  PlyType type;      ///< scalar type, or item type of a list
  PlyType countType; ///< count type of a list, Invalid for a scalar
  bool isList() const { return countType != PlyType::Invalid; }
};

/** \internal One element of a PLY header. */
struct PlyElement
{
  std::string name;
  unsigned long long count;
  std::vector<PlyProperty> properties;
};

/** \internal Supplies the values of a PLY body one by one: ascii tokens (any line structure) or
  * binary values of a given byte order. where() names the place of the last value for errors. */
class PlyValueSource
{
public:
  PlyValueSource(OffLineReader& reader, bool ascii, bool bigEndian) : m_reader(reader), m_ascii(ascii), m_position(nullptr)
  {
    const std::uint16_t probe = 1;
    unsigned char firstByte;
    std::memcpy(&firstByte, &probe, 1);
    m_swap = (firstByte == 1) == bigEndian;
    m_line.clear();
  }

  /** Reads the next value as a double. \returns false at the end of the data, on a read error or
    * (ascii) on a token that is not a number or that a value of \a type cannot hold (a fraction or
    * an out-of-range number for an integer type, a number beyond float's range for float; binary
    * values are of the type by construction); problem() then says which. */
  bool next(PlyType type, double& value)
  {
    if (!m_ascii)
    {
      m_offset = m_reader.byteOffset();
      unsigned char bytes[8];
      if (!m_reader.readBytes(bytes, plyTypeSize(type))) return endOfData();
      value = plyDecode(bytes, type, m_swap);
      return true;
    }
    while (m_position == nullptr || offOnlySpaceLeft(m_position))
    {
      if (!m_reader.nextDataLine(m_line)) return endOfData();
      m_position = m_line.c_str();
    }
    const char* tokenBegin = m_position;
    while (std::isspace(static_cast<unsigned char>(*tokenBegin))) ++tokenBegin;
    auto token = [tokenBegin]() {
      const char* tokenEnd = tokenBegin;
      while (*tokenEnd && !std::isspace(static_cast<unsigned char>(*tokenEnd))) ++tokenEnd;
      return "'" + std::string(tokenBegin, tokenEnd).substr(0, 32) + "'";
    };
    if (!offParseDouble(m_position, value))
    {
      m_problem = token() + " is not a number";
      return false;
    }
    if (!plyValueFits(type, value))
    {
      m_problem = token() + " does not fit the declared type " + plyTypeName(type) + " (" + plyTypeRange(type) + ")";
      return false;
    }
    return true;
  }

  /** \returns whether data is left after the last value read. */
  bool hasMoreData()
  {
    if (!m_ascii) return m_reader.hasMoreBytes();
    if (m_position != nullptr && !offOnlySpaceLeft(m_position)) return true;
    return m_reader.nextDataLine(m_line);
  }

  /** \returns "line N" (ascii) or "byte B" (binary) for the last value read. */
  std::string where() const
  {
    return m_ascii ? "line " + std::to_string(m_reader.lineNumber()) : "byte " + std::to_string(m_offset);
  }

  /** \returns what went wrong in the last failed next(). */
  const std::string& problem() const { return m_problem; }

private:
  bool endOfData()
  {
    const std::string streamError = m_reader.streamError();
    m_problem = streamError.empty() ? "file ends early (truncated?)" : "read error (" + streamError + ")";
    return false;
  }

  OffLineReader& m_reader;
  bool m_ascii, m_swap;
  std::string m_line, m_problem;
  const char* m_position;
  long long m_offset = 0;
};

/** \internal Splits \a line into white-space separated words. */
inline std::vector<std::string> plySplitWords(const std::string& line)
{
  std::vector<std::string> words;
  const char* p = line.c_str();
  while (*p)
  {
    while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
    const char* begin = p;
    while (*p && !std::isspace(static_cast<unsigned char>(*p))) ++p;
    if (p > begin) words.emplace_back(begin, p);
  }
  return words;
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Reads a triangle mesh from a PLY file (ascii or binary, either byte order), plain or
  * gzip-compressed.
  *
  * The header must start with \c ply and a \c format line; \c comment and \c obj_info lines are
  * ignored. The \c vertex element must have scalar properties \c x, \c y, \c z (of any PLY type:
  * char/int8 ... double/float64); the optional \c face element a list property \c vertex_indices
  * (or \c vertex_index) of any count and index type; each face of k >= 3 corners becomes the fan
  * (i_1, i_j, i_{j+1}). All other properties and elements are read and skipped. In ascii files the
  * values may be spread over lines in any way. No data may follow the last element.
  *
  * \param path   file to read; gzip-compressed and plain files are both accepted.
  * \param V      on success, the #V x 3 vertex positions.
  * \param F      on success, the #F x 3 triangles (0-based, file orientation kept).
  * \param error  if not null, receives a message naming the file and the line (header, ascii body)
  *               or the byte offset (binary body) when reading fails, and is cleared on success.
  * \returns true on success. On failure (bad header, truncated body, index out of range or not an
  *          integer, non-finite coordinate, face with fewer than 3 corners, count that does not
  *          fit, an ascii value that its declared type cannot hold: a fraction or a number out of
  *          range for an integer type, a number beyond float's range for float) \a V and \a F
  *          are left unchanged.
  *
  * \sa readMesh(), writeMesh(), readOFF(), readOBJ()
  */
inline bool readPLY(const std::string& path, Eigen::MatrixXd& V, Eigen::MatrixXi& F, std::string* error = nullptr)
{
  using namespace internal::meshtools;
  internal::OffLineReader reader(path);
  auto failAt = [&](const std::string& where, const std::string& what) {
    return internal::meshFileFailure(error, "readPLY", path, where, what);
  };
  auto fail = [&](const std::string& what) {
    return failAt(reader.isOpen() && reader.lineNumber() > 0 ? "line " + std::to_string(reader.lineNumber())
                                                             : std::string(),
                  what);
  };
  auto endOfHeader = [&]() {
    const std::string streamError = reader.streamError();
    return fail(streamError.empty() ? "file ends inside the header (no end_header)" : "read error (" + streamError + ")");
  };
  if (!reader.isOpen()) return fail("cannot open file (" + reader.openError() + ")");

  try
  {
    // ---- header ------------------------------------------------------------------------------
    std::string line;
    if (!reader.nextDataLine(line)) return endOfHeader();
    std::vector<std::string> words = plySplitWords(line);
    if (words.size() != 1 || words[0] != "ply") return fail("not a PLY file (the first line must be 'ply')");
    int format = -1; // 0 ascii, 1 little endian, 2 big endian
    std::vector<PlyElement> elements;
    for (;;)
    {
      if (!reader.nextDataLine(line)) return endOfHeader();
      words = plySplitWords(line);
      const std::string& keyword = words[0];
      if (keyword == "end_header")
      {
        if (words.size() != 1) return fail("unexpected text after end_header");
        break;
      }
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "format")
      {
        if (format >= 0) return fail("second format line");
        if (words.size() != 3 || words[2] != "1.0") return fail("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
        if (words[1] == "ascii") format = 0;
        else if (words[1] == "binary_little_endian") format = 1;
        else if (words[1] == "binary_big_endian") format = 2;
        else return fail("unknown format '" + words[1].substr(0, 32) + "'");
      }
      else if (keyword == "element")
      {
        if (words.size() != 3) return fail("expected 'element <name> <count>'");
        const std::string& countText = words[2];
        if (countText.empty() || countText.size() > 18 ||
            countText.find_first_not_of("0123456789") != std::string::npos)
          return fail("element '" + words[1].substr(0, 32) + "': count '" + countText.substr(0, 32) +
                      "' is not a non-negative integer below 10^18");
        for (const PlyElement& e : elements)
          if (e.name == words[1]) return fail("element '" + words[1].substr(0, 32) + "' declared twice");
        elements.push_back({words[1], std::stoull(countText), {}});
      }
      else if (keyword == "property")
      {
        if (elements.empty()) return fail("property before any element");
        PlyProperty property;
        if (words.size() == 5 && words[1] == "list")
        {
          property.countType = plyTypeFromName(words[2]);
          property.type = plyTypeFromName(words[3]);
          property.name = words[4];
          if (property.countType == PlyType::Invalid || property.type == PlyType::Invalid)
            return fail("unknown property type in list property '" + property.name.substr(0, 32) + "'");
          if (property.countType == PlyType::Float32 || property.countType == PlyType::Float64)
            return fail("list property '" + property.name.substr(0, 32) + "' has a floating-point count type");
        }
        else if (words.size() == 3)
        {
          property.type = plyTypeFromName(words[1]);
          property.countType = PlyType::Invalid;
          property.name = words[2];
          if (property.type == PlyType::Invalid) return fail("unknown property type '" + words[1].substr(0, 32) + "'");
        }
        else return fail("expected 'property <type> <name>' or 'property list <count type> <item type> <name>'");
        for (const PlyProperty& other : elements.back().properties)
          if (other.name == property.name) return fail("property '" + property.name.substr(0, 32) + "' declared twice");
        elements.back().properties.push_back(property);
      }
      else return fail("unknown header keyword '" + keyword.substr(0, 32) + "'");
    }
    const long headerEndLine = reader.lineNumber();
    if (format < 0) return fail("no format line in the header");

    // ---- which element and properties hold the mesh --------------------------------------------
    int vertexElement = -1, faceElement = -1, faceList = -1;
    int coordinate[3] = {-1, -1, -1};
    for (int e = 0; e < int(elements.size()); ++e)
    {
      const PlyElement& element = elements[std::size_t(e)];
      if (element.name == "vertex")
      {
        vertexElement = e;
        for (int p = 0; p < int(element.properties.size()); ++p)
          for (int c = 0; c < 3; ++c)
            if (element.properties[std::size_t(p)].name == std::string(1, char('x' + c)))
            {
              if (element.properties[std::size_t(p)].isList())
                return fail("vertex property '" + std::string(1, char('x' + c)) + "' is a list");
              coordinate[c] = p;
            }
        for (int c = 0; c < 3; ++c)
          if (coordinate[c] < 0) return fail("the vertex element has no '" + std::string(1, char('x' + c)) + "' property");
      }
      else if (element.name == "face")
      {
        faceElement = e;
        for (int p = 0; p < int(element.properties.size()); ++p)
        {
          const PlyProperty& property = element.properties[std::size_t(p)];
          if (property.isList() && (property.name == "vertex_indices" || property.name == "vertex_index")) faceList = p;
        }
        if (faceList < 0 && element.count > 0) return fail("the face element has no 'vertex_indices' list property");
      }
    }
    const unsigned long long vertexCount = vertexElement >= 0 ? elements[std::size_t(vertexElement)].count : 0;
    const unsigned long long faceCount = faceElement >= 0 ? elements[std::size_t(faceElement)].count : 0;
    if (vertexCount > (unsigned long long)std::numeric_limits<int>::max() ||
        faceCount > (unsigned long long)std::numeric_limits<int>::max())
      return fail("vertex or face count does not fit into int (header line " + std::to_string(headerEndLine) + ")");

    // ---- body ----------------------------------------------------------------------------------
    PlyValueSource source(reader, format == 0, format == 2);
    auto failValue = [&](const std::string& what) { return failAt(source.where(), what); };
    const std::size_t reserveCap = std::size_t(1) << 20; // growth beyond this follows the data, not the header
    std::vector<double> coords;
    coords.reserve(3 * std::min<std::size_t>(std::size_t(vertexCount), reserveCap));
    std::vector<int> tris, corners;
    tris.reserve(3 * std::min<std::size_t>(std::size_t(faceCount), reserveCap));
    for (int e = 0; e < int(elements.size()); ++e)
    {
      const PlyElement& element = elements[std::size_t(e)];
      if (element.properties.empty()) continue; // items without properties take no space
      for (unsigned long long item = 0; item < element.count; ++item)
      {
        auto itemName = [&]() { return element.name.substr(0, 32) + " " + std::to_string(item); };
        double point[3] = {0, 0, 0};
        for (int p = 0; p < int(element.properties.size()); ++p)
        {
          const PlyProperty& property = element.properties[std::size_t(p)];
          double value;
          if (!property.isList())
          {
            if (!source.next(property.type, value)) return failValue(itemName() + ": " + source.problem());
            if (e == vertexElement)
              for (int c = 0; c < 3; ++c)
                if (p == coordinate[c])
                {
                  if (!std::isfinite(value)) return failValue("vertex " + std::to_string(item) + " has a non-finite coordinate");
                  point[c] = value;
                }
            continue;
          }
          double countValue;
          if (!source.next(property.countType, countValue)) return failValue(itemName() + ": " + source.problem());
          if (!(countValue >= 0) || countValue != std::floor(countValue) || countValue > 4294967295.0)
            return failValue(itemName() + ": list count is not a non-negative integer");
          const unsigned long long count = (unsigned long long)countValue;
          const bool isFace = e == faceElement && p == faceList;
          if (isFace && count < 3)
            return failValue("face " + std::to_string(item) + " has " + std::to_string(count) + " corners (need at least 3)");
          if (isFace && count > vertexCount)
            return failValue("face " + std::to_string(item) + " has more corners (" + std::to_string(count) +
                             ") than the mesh has vertices");
          corners.clear();
          for (unsigned long long k = 0; k < count; ++k)
          {
            if (!source.next(property.type, value)) return failValue(itemName() + ": " + source.problem());
            if (!isFace) continue;
            if (!(value >= 0 && value < double(vertexCount)) || value != std::floor(value))
              return failValue("face " + std::to_string(item) + ": vertex index " + std::to_string(value) +
                               " is not an integer in [0, " + std::to_string(vertexCount) + ")");
            corners.push_back(int(value));
          }
          for (std::size_t c = 1; c + 1 < corners.size(); ++c)
          {
            tris.push_back(corners[0]);
            tris.push_back(corners[c]);
            tris.push_back(corners[c + 1]);
          }
        }
        if (e == vertexElement) coords.insert(coords.end(), point, point + 3);
      }
    }
    if (source.hasMoreData())
      return failAt(format == 0 ? "line " + std::to_string(reader.lineNumber()) : "byte " + std::to_string(reader.byteOffset()),
                    "more data than the header declares");
    return internal::meshReadFinish(reader, coords, tris, V, F, error, fail);
  }
  catch (const std::bad_alloc&)
  {
    return fail("out of memory");
  }
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_READPLY_H
