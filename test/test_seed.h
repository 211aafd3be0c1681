// The seed offset of the tests' random sequences: 0 unless the environment variable
// UC_TEST_SEED_OFFSET says otherwise, so that the same checks can be run on other sequences
// (fuzzing) without changing what ctest runs.
#ifndef UC_TEST_SEED_H
#define UC_TEST_SEED_H

#include <cstdlib>

namespace uctest {

/** Added to the seeds of the random update, cut and merge sequences (test_updates,
  * test_insert_dofs) and of the seam edit sessions (test_parameterization), e.g.
  * `for o in 100 200 300; do UC_TEST_SEED_OFFSET=$o build/test/test_insert_dofs; done`. */
inline unsigned seedOffset() {
  const char* text = std::getenv("UC_TEST_SEED_OFFSET");
  return text ? unsigned(std::strtoul(text, nullptr, 10)) : 0u;
}

}  // namespace uctest

#endif  // UC_TEST_SEED_H
