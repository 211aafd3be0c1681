// RenderMesh: small software renderers that write PNG pictures of meshes, for the tutorials, the
// demo and visual checks of parameterizations: the uv layout filled with a checkerboard (flipped
// triangles in red), and an orthographic, z-buffered, Lambert-shaded view of a 3-D mesh, plain or
// textured with the checkerboard of its uv coordinates.
// Triangles are scan-converted by barycentric coordinates at pixel centres; edges are 1-pixel lines.

#ifndef EIGEN_MESHTOOLS_RENDERMESH_H
#define EIGEN_MESHTOOLS_RENDERMESH_H

namespace Eigen {

namespace internal {
namespace meshtools {

/** \internal An RGB picture with an optional depth buffer, and the drawing primitives the
  * renderers need. Pixel (x, y) has its centre at (x + 0.5, y + 0.5); y grows downwards. */
class Canvas
{
public:
  /** A white \a size x \a size picture whose depth buffer holds -infinity. */
  explicit Canvas(int size)
      : m_size(size), m_rgb(std::size_t(size) * std::size_t(size) * 3, 255),
        m_depth(std::size_t(size) * std::size_t(size), -std::numeric_limits<double>::infinity())
  {
  }

  /** \returns the pixels, rows from the top, 3 bytes per pixel. */
  const std::vector<std::uint8_t>& rgb() const { return m_rgb; }

  /** \returns the side length in pixels. */
  int size() const { return m_size; }

  /** Sets pixel (x, y) to \a color if it lies inside the picture. */
  void put(int x, int y, const std::array<std::uint8_t, 3>& color)
  {
    if (x < 0 || y < 0 || x >= m_size || y >= m_size) return;
    std::uint8_t* p = &m_rgb[(std::size_t(y) * std::size_t(m_size) + std::size_t(x)) * 3];
    p[0] = color[0];
    p[1] = color[1];
    p[2] = color[2];
  }

  /** Calls \a shade(x, y, b0, b1, b2) for every pixel centre inside the triangle with corners
    * \a a, \a b, \a c (picture coordinates), b the barycentric coordinates of the centre.
    * Either orientation is accepted; degenerate triangles draw nothing. */
  template <typename Shade>
  void fillTriangle(const Vector2d& a, const Vector2d& b, const Vector2d& c, Shade&& shade) const
  {
    const double area = cross(b - a, c - a);
    if (!(std::abs(area) > 0.0) || !std::isfinite(area)) return;
    const int x0 = std::max(0, int(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(m_size - 1, int(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, int(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(m_size - 1, int(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
      {
        const Vector2d p(x + 0.5, y + 0.5);
        const double w0 = cross(b - p, c - p) / area, w1 = cross(c - p, a - p) / area, w2 = 1.0 - w0 - w1;
        if (w0 >= 0 && w1 >= 0 && w2 >= 0) shade(x, y, w0, w1, w2);
      }
  }

  /** Draws a 1-pixel line from \a a to \a b; with depths \a za, \a zb it only covers pixels
    * whose stored depth is at most \a tolerance in front of the line. */
  void drawLine(const Vector2d& a, const Vector2d& b, const std::array<std::uint8_t, 3>& color,
                double za = 0, double zb = 0, double tolerance = std::numeric_limits<double>::infinity())
  {
    const int steps = std::max(1, int(std::ceil(std::max(std::abs(b.x() - a.x()), std::abs(b.y() - a.y())))));
    for (int s = 0; s <= steps; ++s)
    {
      const double t = double(s) / steps;
      const Vector2d p = (1 - t) * a + t * b;
      const int x = int(std::floor(p.x())), y = int(std::floor(p.y()));
      if (x < 0 || y < 0 || x >= m_size || y >= m_size) continue;
      if (depth(x, y) > (1 - t) * za + t * zb + tolerance) continue;
      put(x, y, color);
    }
  }

  /** Draws a filled disk of \a radius pixels at \a centre, hidden where the stored depth is more
    * than \a tolerance in front of \a z. */
  void drawDot(const Vector2d& centre, double radius, const std::array<std::uint8_t, 3>& color, double z = 0,
               double tolerance = std::numeric_limits<double>::infinity())
  {
    const int cx = int(std::floor(centre.x())), cy = int(std::floor(centre.y()));
    if (cx >= 0 && cy >= 0 && cx < m_size && cy < m_size && depth(cx, cy) > z + tolerance) return;
    const int r = int(std::ceil(radius));
    for (int y = cy - r; y <= cy + r; ++y)
      for (int x = cx - r; x <= cx + r; ++x)
        if ((Vector2d(x + 0.5, y + 0.5) - centre).squaredNorm() <= radius * radius) put(x, y, color);
  }

  /** \returns the depth stored at pixel (x, y) (which must be inside). */
  double& depth(int x, int y) { return m_depth[std::size_t(y) * std::size_t(m_size) + std::size_t(x)]; }

  /** \returns the z component of the cross product of two plane vectors. */
  static double cross(const Vector2d& u, const Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

private:
  int m_size;
  std::vector<std::uint8_t> m_rgb;
  std::vector<double> m_depth;
};

/** \internal Maps points of a bounding box to picture coordinates: uniform scale, centred, a 4%
  * margin, y pointing up in the input and down in the picture. */
class PictureFrame
{
public:
  /** Frames the rows of \a points (#points x 2, at least the first two columns are used). */
  PictureFrame(const MatrixXd& points, int size) : m_size(size), m_scale(1), m_centre(0, 0)
  {
    if (points.rows() == 0) return;
    const Vector2d low = points.leftCols(2).colwise().minCoeff().transpose();
    const Vector2d high = points.leftCols(2).colwise().maxCoeff().transpose();
    const double extent = std::max(high.x() - low.x(), high.y() - low.y());
    m_scale = extent > 0 && std::isfinite(extent) ? 0.92 * size / extent : 1.0;
    m_centre = 0.5 * (low + high);
  }

  /** \returns the picture position of the plane point (u, v). */
  Vector2d operator()(double u, double v) const
  {
    return Vector2d(0.5 * m_size + m_scale * (u - m_centre.x()), 0.5 * m_size - m_scale * (v - m_centre.y()));
  }

private:
  int m_size;
  double m_scale;
  Vector2d m_centre;
};

/** \internal Checks the common arguments of the renderers; \returns an empty string or a message. */
inline std::string renderCheckInput(const MatrixXd& points, Index minColumns, const MatrixXi& F, int size)
{
  if (size < 8 || size > 16384) return "picture size must be in [8, 16384]";
  if (points.cols() < minColumns) return "vertex matrix needs at least " + std::to_string(minColumns) + " columns";
  if (F.rows() > 0 && F.cols() != 3) return "faces must have 3 columns";
  if (F.rows() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= points.rows())) return "face index out of range";
  if (!points.allFinite()) return "vertex coordinates must be finite";
  return std::string();
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Draws the uv layout of a parameterization filled with a checkerboard and writes it as PNG.
  *
  * The layout is scaled uniformly to fit a \a size x \a size picture (u to the right, v up). Each
  * triangle is filled with a \a checks x \a checks checkerboard spanning the longer side of the
  * layout's bounding box, its edges are drawn as thin dark lines (on dense meshes, whose edges
  * average less than 5 pixels on screen, only the boundary edges), and a triangle whose uv orientation
  * differs from the layout's overall orientation (the sign of the total signed area), or has zero
  * area, is filled in red: a flipped triangle.
  *
  * \param UV      #V x 2 uv coordinates (more columns are ignored).
  * \param F       #F x 3 triangles indexing the rows of UV.
  * \param path    PNG file to write.
  * \param size    picture width and height in pixels, in [8, 16384].
  * \param checks  checkerboard squares along the longer side (>= 1).
  * \param error   if not null, receives a message naming the file when something is wrong.
  * \returns true when the picture was written.
  *
  * \sa renderMeshShaded(), writePNG()
  */
inline bool renderUVCheckerboard(const MatrixXd& UV, const MatrixXi& F, const std::string& path, int size = 800,
                                 int checks = 20, std::string* error = nullptr)
{
  using internal::meshtools::Canvas;
  const std::string problem = internal::meshtools::renderCheckInput(UV, 2, F, size);
  if (!problem.empty() || checks < 1)
  {
    if (error) *error = path + ": " + (problem.empty() ? std::string("checks must be >= 1") : problem);
    return false;
  }
  Canvas canvas(size);
  const internal::meshtools::PictureFrame frame(UV, size);
  const double extent = UV.rows() ? (UV.leftCols(2).colwise().maxCoeff() - UV.leftCols(2).colwise().minCoeff()).maxCoeff() : 1.0;
  const double squareSize = extent > 0 ? extent / checks : 1.0;
  const Vector2d origin = UV.rows() ? Vector2d(UV.col(0).minCoeff(), UV.col(1).minCoeff()) : Vector2d(0, 0);

  auto signedArea = [&](Index f) {
    const Vector2d a = UV.row(F(f, 0)).head<2>().transpose(), b = UV.row(F(f, 1)).head<2>().transpose(),
                   c = UV.row(F(f, 2)).head<2>().transpose();
    return 0.5 * Canvas::cross(b - a, c - a);
  };
  double totalArea = 0;
  for (Index f = 0; f < F.rows(); ++f) totalArea += signedArea(f);
  const double orientation = totalArea < 0 ? -1.0 : 1.0;

  const std::array<std::uint8_t, 3> light = {235, 235, 235}, dark = {70, 110, 190}, red = {230, 20, 20},
                                    edge = {40, 40, 40};
  for (Index f = 0; f < F.rows(); ++f)
  {
    const bool flipped = !(orientation * signedArea(f) > 0);
    Vector2d uv[3], pixel[3];
    for (int c = 0; c < 3; ++c)
    {
      uv[c] = UV.row(F(f, c)).head<2>().transpose();
      pixel[c] = frame(uv[c].x(), uv[c].y());
    }
    canvas.fillTriangle(pixel[0], pixel[1], pixel[2], [&](int x, int y, double w0, double w1, double w2) {
      if (flipped)
      {
        canvas.put(x, y, red);
        return;
      }
      const Vector2d p = w0 * uv[0] + w1 * uv[1] + w2 * uv[2] - origin;
      const long parity = long(std::floor(p.x() / squareSize)) + long(std::floor(p.y() / squareSize));
      canvas.put(x, y, (parity & 1) ? dark : light);
    });
  }
  // Edges after all fills, so that no fill covers them: boundary edges always, the others only
  // when they are long enough on screen (mean >= 5 pixels) not to hide the checkerboard; flipped
  // triangles get red edges, so that a sliver stays visible.
  const std::vector<int> partner = internal::meshtools::sidePartners(F);
  double pixelLength = 0;
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      pixelLength += (frame(UV(F(f, c), 0), UV(F(f, c), 1)) - frame(UV(F(f, (c + 1) % 3), 0), UV(F(f, (c + 1) % 3), 1))).norm();
  const bool drawInterior = F.rows() > 0 && pixelLength / double(3 * F.rows()) >= 5.0;
  for (Index f = 0; f < F.rows(); ++f)
  {
    const bool flipped = !(orientation * signedArea(f) > 0);
    for (int c = 0; c < 3; ++c)
    {
      if (!flipped && !drawInterior && partner[std::size_t(3 * f + c)] != -1) continue;
      const int a = F(f, c), b = F(f, (c + 1) % 3);
      canvas.drawLine(frame(UV(a, 0), UV(a, 1)), frame(UV(b, 0), UV(b, 1)), flipped ? red : edge);
    }
  }
  return writePNG(path, size, size, canvas.rgb(), error);
}

namespace internal {
namespace meshtools {

/** \internal The renderer behind renderMeshShaded() and renderMeshCheckerboard(): with \a UV null
  * the surface colour is uniform, otherwise a \a checks x \a checks checkerboard over the uv
  * bounding box's longer side, interpolated per pixel. */
inline bool renderShaded(const MatrixXd& V, const MatrixXi& F, const MatrixXd* UV, int checks, const std::string& path,
                         const Matrix3d& rotation, int size, const std::vector<int>& highlightVertices,
                         std::string* error)
{
  std::string problem = renderCheckInput(V, 3, F, size);
  for (int v : highlightVertices)
    if (problem.empty() && (v < 0 || v >= V.rows())) problem = "highlighted vertex " + std::to_string(v) + " out of range";
  if (problem.empty() && !rotation.allFinite()) problem = "rotation must be finite";
  if (problem.empty() && UV && (UV->rows() != V.rows() || UV->cols() < 2 || !UV->allFinite()))
    problem = "UV must be #V x 2 and finite";
  if (problem.empty() && checks < 1) problem = "checks must be >= 1";
  if (!problem.empty())
  {
    if (error) *error = path + ": " + problem;
    return false;
  }
  const MatrixXd P = V.leftCols(3) * rotation.transpose();
  Canvas canvas(size);
  const PictureFrame frame(P, size);
  const double depthExtent = P.rows() ? P.col(2).maxCoeff() - P.col(2).minCoeff() : 1.0;
  double squareSize = 1;
  Vector2d uvOrigin(0, 0);
  if (UV && UV->rows() > 0)
  {
    const double extent = (UV->leftCols(2).colwise().maxCoeff() - UV->leftCols(2).colwise().minCoeff()).maxCoeff();
    squareSize = extent > 0 ? extent / checks : 1.0;
    uvOrigin << UV->col(0).minCoeff(), UV->col(1).minCoeff();
  }
  for (Index f = 0; f < F.rows(); ++f)
  {
    const Vector3d a = P.row(F(f, 0)).transpose(), b = P.row(F(f, 1)).transpose(), c = P.row(F(f, 2)).transpose();
    const Vector3d normal = (b - a).cross(c - a);
    const double length = normal.norm();
    if (!(length > 0)) continue;
    const double brightness = 0.25 + 0.75 * std::abs(normal.z()) / length;
    canvas.fillTriangle(frame(a.x(), a.y()), frame(b.x(), b.y()), frame(c.x(), c.y()),
                        [&](int x, int y, double w0, double w1, double w2) {
                          const double z = w0 * a.z() + w1 * b.z() + w2 * c.z();
                          double& stored = canvas.depth(x, y);
                          if (z <= stored) return;
                          stored = z;
                          Vector3d base(200, 205, 225);
                          if (UV)
                          {
                            const Vector2d p = w0 * UV->row(F(f, 0)).head<2>().transpose() +
                                               w1 * UV->row(F(f, 1)).head<2>().transpose() +
                                               w2 * UV->row(F(f, 2)).head<2>().transpose() - uvOrigin;
                            const long parity = long(std::floor(p.x() / squareSize)) + long(std::floor(p.y() / squareSize));
                            base = (parity & 1) ? Vector3d(70, 110, 190) : Vector3d(240, 240, 240);
                          }
                          canvas.put(x, y, {std::uint8_t(std::lround(base[0] * brightness)),
                                            std::uint8_t(std::lround(base[1] * brightness)),
                                            std::uint8_t(std::lround(base[2] * brightness))});
                        });
  }
  const double radius = std::max(1.5, size / 250.0);
  for (int v : highlightVertices)
    canvas.drawDot(frame(P(v, 0), P(v, 1)), radius, {220, 20, 20}, P(v, 2), 0.02 * depthExtent);
  return writePNG(path, size, size, canvas.rgb(), error);
}

} // namespace meshtools
} // namespace internal

/** \ingroup MeshTools_Module
  * \brief Draws an orthographic, z-buffered, Lambert-shaded picture of a 3-D mesh and writes it as PNG.
  *
  * The vertices are rotated by \a rotation, then projected along z onto the xy plane (x to the right,
  * y up, the viewer on the +z side), scaled to fit the picture. Each pixel shows the nearest
  * triangle, with brightness 0.25 + 0.75 |n.z| (two-sided Lambert shading under a light at the
  * viewer, n the unit triangle normal). Highlighted vertices are drawn as red dots where they are
  * not hidden by the surface.
  *
  * \param V                  #V x 3 vertex positions.
  * \param F                  #F x 3 triangles.
  * \param path               PNG file to write.
  * \param rotation           rotation applied to the vertices before projecting (Identity: look down -z).
  * \param size               picture width and height in pixels, in [8, 16384].
  * \param highlightVertices  vertices to mark with dots (indices outside [0, #V) are an error).
  * \param error              if not null, receives a message naming the file when something is wrong.
  * \returns true when the picture was written.
  *
  * \sa renderMeshCheckerboard(), renderUVCheckerboard(), writePNG()
  */
inline bool renderMeshShaded(const MatrixXd& V, const MatrixXi& F, const std::string& path,
                             const Matrix3d& rotation = Matrix3d::Identity(), int size = 800,
                             const std::vector<int>& highlightVertices = {}, std::string* error = nullptr)
{
  return internal::meshtools::renderShaded(V, F, nullptr, 1, path, rotation, size, highlightVertices, error);
}

/** \ingroup MeshTools_Module
  * \brief Draws the 3-D mesh as renderMeshShaded() does, textured with the checkerboard of its uv
  * coordinates: a conformal map keeps the squares square on the surface, and area distortion shows
  * as squares of different sizes.
  *
  * \param V        #V x 3 vertex positions (e.g. a parameterization's cut vertices).
  * \param F        #F x 3 triangles.
  * \param UV       #V x 2 uv coordinates of the same vertices.
  * \param path     PNG file to write.
  * \param rotation rotation applied to the vertices before projecting.
  * \param size     picture width and height in pixels, in [8, 16384].
  * \param checks   checkerboard squares along the longer side of the uv bounding box (>= 1).
  * \param error    if not null, receives a message naming the file when something is wrong.
  * \returns true when the picture was written.
  *
  * \sa renderMeshShaded(), renderUVCheckerboard()
  */
inline bool renderMeshCheckerboard(const MatrixXd& V, const MatrixXi& F, const MatrixXd& UV, const std::string& path,
                                   const Matrix3d& rotation = Matrix3d::Identity(), int size = 800, int checks = 20,
                                   std::string* error = nullptr)
{
  return internal::meshtools::renderShaded(V, F, &UV, checks, path, rotation, size, {}, error);
}

} // namespace Eigen

#endif // EIGEN_MESHTOOLS_RENDERMESH_H
