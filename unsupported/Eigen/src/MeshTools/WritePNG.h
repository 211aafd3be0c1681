// WritePNG: writes an 8-bit RGB image as a PNG file (ISO/IEC 15948): signature, IHDR, one IDAT
// chunk holding the zlib-deflated scanlines (filter type 0), IEND. CRCs come from zlib's crc32().
// Used by the renderers (RenderMesh.h) of the tutorials, the demo and the tests.

#ifndef EIGEN_MESHTOOLS_WRITEPNG_H
#define EIGEN_MESHTOOLS_WRITEPNG_H

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal Appends \a value as 4 big-endian bytes to \a out. */
inline void pngPutUint32(std::vector<std::uint8_t>& out, std::uint32_t value)
{
  out.push_back(std::uint8_t(value >> 24));
  out.push_back(std::uint8_t(value >> 16));
  out.push_back(std::uint8_t(value >> 8));
  out.push_back(std::uint8_t(value));
}

/** \internal Appends one PNG chunk (length, type, data, CRC of type and data) to \a out. */
inline void pngPutChunk(std::vector<std::uint8_t>& out, const char type[4], const std::uint8_t* data, std::size_t size)
{
  pngPutUint32(out, std::uint32_t(size));
  const std::size_t typeStart = out.size();
  out.insert(out.end(), type, type + 4);
  if (size) out.insert(out.end(), data, data + size);
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, out.data() + typeStart, uInt(4 + size));
  pngPutUint32(out, std::uint32_t(crc));
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Writes an 8-bit RGB image to a PNG file.
  *
  * \param path    file to write (created or overwritten).
  * \param width   image width in pixels (>= 1).
  * \param height  image height in pixels (>= 1).
  * \param rgb     width*height*3 bytes: pixels row by row from the top row, each as R, G, B.
  * \param error   if not null, receives a message naming the file when writing fails.
  * \returns true on success; false (nothing or a partial file written) on bad sizes, when
  *          compression fails or the file cannot be written.
  *
  * \sa renderUVCheckerboard(), renderMeshShaded()
  */
inline bool writePNG(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb,
                     std::string* error = nullptr)
{
  auto fail = [&](const std::string& message) {
    if (error) *error = path + ": " + message;
    return false;
  };
  if (width <= 0 || height <= 0) return fail("image size must be positive");
  if (std::uint64_t(width) * std::uint64_t(height) * 3 > std::uint64_t(1) << 31)
    return fail("image too large");
  const std::size_t rowBytes = std::size_t(width) * 3;
  if (rgb.size() != rowBytes * std::size_t(height))
    return fail("expected " + std::to_string(rowBytes * std::size_t(height)) + " bytes of RGB data, got " +
                std::to_string(rgb.size()));

  // Scanlines, each preceded by its filter type (0 = None).
  std::vector<std::uint8_t> raw((rowBytes + 1) * std::size_t(height));
  for (int y = 0; y < height; ++y)
  {
    raw[std::size_t(y) * (rowBytes + 1)] = 0;
    std::memcpy(&raw[std::size_t(y) * (rowBytes + 1) + 1], &rgb[std::size_t(y) * rowBytes], rowBytes);
  }
  uLongf packedSize = compressBound(uLong(raw.size()));
  std::vector<std::uint8_t> packed(packedSize);
  if (compress2(packed.data(), &packedSize, raw.data(), uLong(raw.size()), 6) != Z_OK)
    return fail("zlib compression failed");

  std::vector<std::uint8_t> file = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> header;
  internal::meshtools::pngPutUint32(header, std::uint32_t(width));
  internal::meshtools::pngPutUint32(header, std::uint32_t(height));
  header.insert(header.end(), {8, 2, 0, 0, 0}); // bit depth 8, colour type RGB, deflate, filter 0, no interlace
  internal::meshtools::pngPutChunk(file, "IHDR", header.data(), header.size());
  internal::meshtools::pngPutChunk(file, "IDAT", packed.data(), std::size_t(packedSize));
  internal::meshtools::pngPutChunk(file, "IEND", nullptr, 0);

  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (!out) return fail(std::string("cannot open for writing: ") + std::strerror(errno));
  const bool written = std::fwrite(file.data(), 1, file.size(), out) == file.size();
  const bool closed = std::fclose(out) == 0;
  if (!written || !closed) return fail("write failed");
  if (error) error->clear();
  return true;
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_WRITEPNG_H
