// Consumer check: factors and solves a 1-D Laplacian with the installed library; exits non-zero
// when the residual is not tiny.
#include <Eigen/UpdatableCholesky>
#include <iostream>

int main() {
  const int n = 1000;
  Eigen::SparseMatrix<double> A(n, n);
  std::vector<Eigen::Triplet<double> > t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + 1e-3);
    if (i + 1 < n) t.emplace_back(i + 1, i, -1.0);
  }
  A.setFromTriplets(t.begin(), t.end());
  Eigen::UpdatableSupernodalLLT<Eigen::SparseMatrix<double> > llt(A);
  Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd x = llt.solve(b);
  const double residual = (A.selfadjointView<Eigen::Lower>() * x - b).norm() / b.norm();
  std::cout << "consumer: info " << llt.info() << ", residual " << residual << "\n";
  return (llt.info() == Eigen::Success && residual < 1e-10) ? 0 : 1;
}
