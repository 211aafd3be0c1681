// ReadOBJ: reads the triangles of a Wavefront OBJ file, plain or gzip-compressed (zlib reads
// both): `v` and `f` records (faces in the v, v/vt, v//vn and v/vt/vn forms, negative relative
// indices, polygons fan-triangulated); every other record is ignored. Malformed input makes it
// return false with a message naming the file and the line; it never aborts.

#ifndef EIGEN_MESHTOOLS_READOBJ_H
#define EIGEN_MESHTOOLS_READOBJ_H

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal Parses one face corner of an OBJ `f` record at \a p: an integer vertex reference
  * followed by up to two groups '/' [integer] (texture and normal references, ignored), then
  * white space or the end. Advances \a p. \returns false if the token has another form. */
inline bool objParseCorner(const char*& p, long& vertexReference)
{
  char* end = nullptr;
  errno = 0;
  vertexReference = std::strtol(p, &end, 10);
  if (end == p || errno == ERANGE) return false;
  p = end;
  for (int group = 0; group < 2 && *p == '/'; ++group)
  {
    ++p;
    if (*p == '-' || *p == '+' || std::isdigit(static_cast<unsigned char>(*p)))
    {
      errno = 0;
      std::strtol(p, &end, 10);
      if (end == p || errno == ERANGE) return false;
      p = end;
    }
  }
  return *p == '\0' || std::isspace(static_cast<unsigned char>(*p));
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Reads a triangle mesh from a Wavefront OBJ file, plain or gzip-compressed.
  *
  * Records: <tt>v x y z [w | r g b]</tt> adds a vertex (values after the third are ignored);
  * <tt>f c_1 c_2 ... c_k</tt> with k >= 3 adds the fan (c_1, c_j, c_{j+1}), each corner in one of
  * the forms \c v, \c v/vt, \c v//vn, \c v/vt/vn. Vertex references are 1-based, or negative
  * relative to the vertices read so far (-1 is the last one); a face may only use vertices
  * declared above it. Comments start with '#'. All other records (vt, vn, g, o, s, usemtl, mtllib,
  * l, p, ...) are ignored.
  *
  * \param path   file to read; gzip-compressed and plain files are both accepted.
  * \param V      on success, the #V x 3 vertex positions.
  * \param F      on success, the #F x 3 triangles (0-based, file orientation kept).
  * \param error  if not null, receives a message naming the file and line when reading fails,
  *               and is cleared on success.
  * \returns true on success. On failure (unreadable file, malformed record, reference 0 or out of
  *          range, non-finite coordinate, face with fewer than 3 corners, no vertex record but
  *          lines that are no OBJ record: another format or not text) \a V and \a F are left
  *          unchanged. A file of comments and OBJ records without vertices is an empty mesh.
  *
  * \sa readMesh(), writeMesh(), readOFF(), readPLY()
  */
inline bool readOBJ(const std::string& path, Eigen::MatrixXd& V, Eigen::MatrixXi& F, std::string* error = nullptr)
{
  internal::OffLineReader reader(path);
  auto fail = [&](const std::string& what) {
    return internal::meshFileFailure(error, "readOBJ", path,
                                     reader.isOpen() && reader.lineNumber() > 0
                                         ? "line " + std::to_string(reader.lineNumber())
                                         : std::string(),
                                     what);
  };
  if (!reader.isOpen()) return fail("cannot open file (" + reader.openError() + ")");

  try
  {
    std::vector<double> coords;
    std::vector<int> tris, corners;
    std::string line;
    long foreign = 0;  // lines before the first vertex whose keyword OBJ does not define (another format, or no text)
    static const char* const objKeywords[] = {"vt", "vn", "vp", "g", "o", "s", "l", "p", "mg", "usemtl", "mtllib",
                                              "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm",
                                              "trim", "hole", "scrv", "sp", "end", "con", "bevel", "c_interp",
                                              "d_interp", "lod", "shadow_obj", "trace_obj", "ctech", "stech"};
    while (reader.nextDataLine(line))
    {
      const char* p = line.c_str();
      while (std::isspace(static_cast<unsigned char>(*p))) ++p;
      const char* keywordBegin = p;
      while (*p && !std::isspace(static_cast<unsigned char>(*p))) ++p;
      const std::string keyword(keywordBegin, p);
      const long vertexCount = long(coords.size() / 3);
      if (keyword == "v")
      {
        if (vertexCount >= long(std::numeric_limits<int>::max())) return fail("too many vertices for int indices");
        for (int c = 0; c < 3; ++c)
        {
          double x;
          if (!internal::offParseDouble(p, x)) return fail("vertex " + std::to_string(vertexCount + 1) + ": expected three coordinates");
          if (!std::isfinite(x)) return fail("vertex " + std::to_string(vertexCount + 1) + " has a non-finite coordinate");
          coords.push_back(x);
        }
      }
      else if (keyword == "f")
      {
        corners.clear();
        while (!internal::offOnlySpaceLeft(p))
        {
          while (std::isspace(static_cast<unsigned char>(*p))) ++p;
          const char* tokenBegin = p;
          long reference;
          if (!internal::meshtools::objParseCorner(p, reference))
          {
            const char* tokenEnd = tokenBegin;
            while (*tokenEnd && !std::isspace(static_cast<unsigned char>(*tokenEnd))) ++tokenEnd;
            return fail("malformed face corner '" + std::string(tokenBegin, tokenEnd).substr(0, 32) +
                        "' (expected v, v/vt, v//vn or v/vt/vn)");
          }
          if (reference == 0) return fail("vertex reference 0 (OBJ references start at 1, or are negative)");
          const long index = reference > 0 ? reference - 1 : vertexCount + reference;
          if (index < 0 || index >= vertexCount)
            return fail("vertex reference " + std::to_string(reference) + " out of range (" +
                        std::to_string(vertexCount) + " vertices so far)");
          corners.push_back(int(index));
        }
        if (corners.size() < 3)
          return fail("face has " + std::to_string(corners.size()) + " corners (need at least 3)");
        for (std::size_t c = 1; c + 1 < corners.size(); ++c)
        {
          tris.push_back(corners[0]);
          tris.push_back(corners[c]);
          tris.push_back(corners[c + 1]);
        }
      }
      else if (coords.empty() && std::find_if(std::begin(objKeywords), std::end(objKeywords),
                            [&keyword](const char* k) { return keyword == k; }) == std::end(objKeywords))
        ++foreign;
    }
    if (coords.empty() && foreign > 0)  // (an empty OBJ is comments or OBJ records only)
      return fail("no vertex record ('v x y z') and " + std::to_string(foreign) +
                  " line(s) that are no OBJ record: not an OBJ mesh");
    return internal::meshReadFinish(reader, coords, tris, V, F, error, fail);
  }
  catch (const std::bad_alloc&)
  {
    return fail("out of memory");
  }
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_READOBJ_H
