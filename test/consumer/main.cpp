// Consumer check: factors and solves a 1-D Laplacian with the installed library, and updates it in
// place once; exits non-zero when the residual is not tiny or the update fails.
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
  // an in-place update through the installed headers alone: fix dof 0 to 1, solve, undo
  llt.removeDofs(std::vector<int>{0});
  const bool removed = llt.info() == Eigen::Success;
  Eigen::VectorXd g = Eigen::VectorXd::Ones(n);
  Eigen::MatrixXd xd = llt.solveDirichlet(b, g);
  llt.restoreDofs(std::vector<int>{0});
  const bool ok = removed && llt.info() == Eigen::Success && xd(0, 0) == 1.0;
  std::cout << "consumer: info " << llt.info() << ", residual " << residual << ", update " << (ok ? "ok" : "FAILED")
            << "\n";
  return (llt.info() == Eigen::Success && residual < 1e-10 && ok) ? 0 : 1;
}
