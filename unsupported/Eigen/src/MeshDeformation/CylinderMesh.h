// CylinderMesh: an open triangulated tube (a "bar"), the classic shape to bend and twist with
// deformation methods (Sorkine & Alexa 2007, Fig. 4-5), for the tests, tutorial and benchmark.

#ifndef EIGEN_MESHDEFORMATION_CYLINDERMESH_H
#define EIGEN_MESHDEFORMATION_CYLINDERMESH_H

namespace Eigen {

/** \ingroup MeshDeformation_Module
  * \brief Open cylinder (a tube without caps) of radius \a radius along the z axis, z in [0, length].
  *
  * Vertex (i, j), 0 <= i < around, 0 <= j < along, has index j*around + i and position
  * (radius cos(2 pi i/around), radius sin(2 pi i/around), length j/(along-1)). Each quad is split
  * into two triangles, counter-clockwise seen from outside, so F has 2*around*(along-1) rows. The
  * mesh is an annulus: two boundary loops (the rings j = 0 and j = along-1).
  * With around < 3 or along < 2 the result is empty.
  *
  * \param around  vertices per ring (>= 3).
  * \param along   rings (>= 2).
  * \param radius  tube radius.
  * \param length  tube length.
  * \param V       output: (around*along) x 3 vertex positions.
  * \param F       output: 2*around*(along-1) x 3 triangles, 0-based.
  */
inline void cylinderMesh(int around, int along, double radius, double length, MatrixXd& V, MatrixXi& F)
{
  if (around < 3 || along < 2)
  {
    V.resize(0, 3);
    F.resize(0, 3);
    return;
  }
  const double pi = 3.14159265358979323846;
  V.resize(Index(around) * along, 3);
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i)
    {
      const double angle = 2.0 * pi * i / around;
      V.row(Index(j) * around + i) << radius * std::cos(angle), radius * std::sin(angle), length * j / (along - 1);
    }
  F.resize(2 * Index(around) * (along - 1), 3);
  Index f = 0;
  for (int j = 0; j + 1 < along; ++j)
    for (int i = 0; i < around; ++i)
    {
      const int next = (i + 1) % around;
      const int v00 = j * around + i, v10 = j * around + next, v01 = v00 + around, v11 = v10 + around;
      F.row(f++) << v00, v10, v11;
      F.row(f++) << v00, v11, v01;
    }
}

} // namespace Eigen

#endif // EIGEN_MESHDEFORMATION_CYLINDERMESH_H
