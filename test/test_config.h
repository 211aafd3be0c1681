// Test configurations: the (Scalar, StorageIndex, storage order, UpLo, ordering) combinations the
// suite is templated over, the solver under test and the SimplicialLLT reference for each, and a
// user-defined ordering functor. Every value of every parameter appears in UC_CONFIGS; the
// primary configuration (double, int, ColMajor, Lower, AMD) is the one tested most broadly.
#ifndef UC_TEST_CONFIG_H
#define UC_TEST_CONFIG_H

#include <iostream>  // Eigen/MetisSupport (3.4) uses std::cerr without including <iostream>
#include <complex>
#include <string>
#include <type_traits>

#include <Eigen/UpdatableCholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/OrderingMethods>
#ifdef UC_TEST_HAVE_METIS
#include <Eigen/MetisSupport>
#endif

#include <doctest/doctest.h>

namespace uctest {

using Eigen::Index;

/** A user-defined ordering functor: places the columns in reverse order. It counts its calls so
  * that tests can see that analyzePattern uses the instance returned by ordering(), and that
  * factorize() does not order again. */
template <typename StorageIndex>
struct ReverseOrdering {
  typedef Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, StorageIndex> PermutationType;
  int calls = 0;
  template <typename MatrixType>
  void operator()(const MatrixType& A, PermutationType& Pinv) {
    ++calls;
    const Index n = A.cols();
    Pinv.resize(n);
    for (Index k = 0; k < n; ++k) Pinv.indices()[k] = StorageIndex(n - 1 - k);
  }
};

template <typename Ordering> struct OrderingTraits {  // does the ordering reduce fill on random graphs?
  static constexpr bool fillReducing = false;
};
template <typename I> struct OrderingTraits<Eigen::AMDOrdering<I>> { static constexpr bool fillReducing = true; };
#ifdef UC_TEST_HAVE_METIS
template <typename I> struct OrderingTraits<Eigen::MetisOrdering<I>> { static constexpr bool fillReducing = true; };
#endif

template <typename Scalar_, typename StorageIndex_, int Options_, int UpLo_, typename Ordering_>
struct Config {
  typedef Scalar_ Scalar;
  typedef StorageIndex_ StorageIndex;
  typedef typename Eigen::NumTraits<Scalar>::Real RealScalar;
  typedef Ordering_ Ordering;
  static constexpr int Options = Options_;
  static constexpr int UpLo = UpLo_;
  static constexpr bool fillReducing = OrderingTraits<Ordering>::fillReducing;
  static constexpr bool isComplex = Eigen::NumTraits<Scalar>::IsComplex;
  /** the input matrix type handed to compute()/factorize() */
  typedef Eigen::SparseMatrix<Scalar, Options, StorageIndex> MatrixType;
  /** canonical storage the generators produce: column-major, both triangles */
  typedef Eigen::SparseMatrix<Scalar, Eigen::ColMajor, StorageIndex> FullMatrix;
  typedef Eigen::Matrix<Scalar, Eigen::Dynamic, 1> Vector;
  typedef Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> Dense;
  typedef Eigen::UpdatableSupernodalLLT<MatrixType, UpLo, Ordering> Solver;
  /** the reference: Eigen's SimplicialLLT on the same input, always with AMD (its fill is
    * bounded whatever ordering the solver under test uses) */
  typedef Eigen::SimplicialLLT<MatrixType, UpLo, Eigen::AMDOrdering<StorageIndex>> Reference;
  static constexpr bool isPrimary = std::is_same<Scalar, double>::value && std::is_same<StorageIndex, int>::value &&
                                    Options == Eigen::ColMajor && UpLo == Eigen::Lower &&
                                    std::is_same<Ordering, Eigen::AMDOrdering<int>>::value;
};

using Eigen::AMDOrdering;
using Eigen::ColMajor;
using Eigen::Lower;
using Eigen::NaturalOrdering;
using Eigen::RowMajor;
using Eigen::Upper;
typedef std::complex<float> cfloat;
typedef std::complex<double> cdouble;

// The configurations. Names: scalar _ index _ storage order _ triangle _ ordering.
typedef Config<double, int, ColMajor, Lower, AMDOrdering<int>> d_int_col_lower_amd;  // primary
typedef Config<float, int, ColMajor, Lower, AMDOrdering<int>> f_int_col_lower_amd;
typedef Config<float, long, RowMajor, Upper, ReverseOrdering<long>> f_long_row_upper_rev;
typedef Config<double, long, RowMajor, Lower, AMDOrdering<long>> d_long_row_lower_amd;
typedef Config<double, int, RowMajor, Upper, ReverseOrdering<int>> d_int_row_upper_rev;
typedef Config<double, long, ColMajor, Upper, NaturalOrdering<long>> d_long_col_upper_nat;
typedef Config<cfloat, int, ColMajor, Upper, NaturalOrdering<int>> cf_int_col_upper_nat;
typedef Config<cfloat, long, ColMajor, Lower, AMDOrdering<long>> cf_long_col_lower_amd;
typedef Config<cdouble, long, RowMajor, Upper, AMDOrdering<long>> cd_long_row_upper_amd;
typedef Config<long double, long, ColMajor, Lower, ReverseOrdering<long>> ld_long_col_lower_rev;
typedef Config<long double, int, RowMajor, Upper, AMDOrdering<int>> ld_int_row_upper_amd;
#ifdef UC_TEST_HAVE_METIS
typedef Config<double, int, ColMajor, Upper, Eigen::MetisOrdering<int>> d_int_col_upper_metis;
typedef Config<cdouble, int, ColMajor, Lower, Eigen::MetisOrdering<int>> cd_int_col_lower_metis;
typedef Config<float, int, RowMajor, Lower, Eigen::MetisOrdering<int>> f_int_row_lower_metis;
#define UC_METIS_CONFIGS , d_int_col_upper_metis, cd_int_col_lower_metis, f_int_row_lower_metis
#define UC_METIS_CONFIG_DOUBLE , d_int_col_upper_metis
#else
#define UC_METIS_CONFIGS
#define UC_METIS_CONFIG_DOUBLE
#endif

/** every configuration */
#define UC_CONFIGS                                                                                          \
  uctest::d_int_col_lower_amd, uctest::f_int_col_lower_amd, uctest::f_long_row_upper_rev,                   \
      uctest::d_long_row_lower_amd, uctest::d_int_row_upper_rev, uctest::d_long_col_upper_nat,              \
      uctest::cf_int_col_upper_nat, uctest::cf_long_col_lower_amd,                                          \
      uctest::cd_long_row_upper_amd, uctest::ld_long_col_lower_rev, uctest::ld_int_row_upper_amd UC_METIS_CONFIGS

/** a smaller set that still holds every value of every parameter, for the costlier tests */
#define UC_CORE_CONFIGS                                                                                     \
  uctest::d_int_col_lower_amd, uctest::f_long_row_upper_rev, uctest::d_long_col_upper_nat,                  \
      uctest::cf_long_col_lower_amd, uctest::cd_long_row_upper_amd, uctest::ld_int_row_upper_amd UC_METIS_CONFIG_DOUBLE

}  // namespace uctest

TYPE_TO_STRING_AS("double,int,ColMajor,Lower,AMD", uctest::d_int_col_lower_amd);
TYPE_TO_STRING_AS("float,int,ColMajor,Lower,AMD", uctest::f_int_col_lower_amd);
TYPE_TO_STRING_AS("float,long,RowMajor,Upper,Reverse", uctest::f_long_row_upper_rev);
TYPE_TO_STRING_AS("double,long,RowMajor,Lower,AMD", uctest::d_long_row_lower_amd);
TYPE_TO_STRING_AS("double,int,RowMajor,Upper,Reverse", uctest::d_int_row_upper_rev);
TYPE_TO_STRING_AS("double,long,ColMajor,Upper,Natural", uctest::d_long_col_upper_nat);
TYPE_TO_STRING_AS("complex<float>,int,ColMajor,Upper,Natural", uctest::cf_int_col_upper_nat);
TYPE_TO_STRING_AS("complex<float>,long,ColMajor,Lower,AMD", uctest::cf_long_col_lower_amd);
TYPE_TO_STRING_AS("complex<double>,long,RowMajor,Upper,AMD", uctest::cd_long_row_upper_amd);
TYPE_TO_STRING_AS("long double,long,ColMajor,Lower,Reverse", uctest::ld_long_col_lower_rev);
TYPE_TO_STRING_AS("long double,int,RowMajor,Upper,AMD", uctest::ld_int_row_upper_amd);
#ifdef UC_TEST_HAVE_METIS
TYPE_TO_STRING_AS("double,int,ColMajor,Upper,Metis", uctest::d_int_col_upper_metis);
TYPE_TO_STRING_AS("complex<double>,int,ColMajor,Lower,Metis", uctest::cd_int_col_lower_metis);
TYPE_TO_STRING_AS("float,int,RowMajor,Lower,Metis", uctest::f_int_row_lower_metis);
#endif

#endif  // UC_TEST_CONFIG_H
