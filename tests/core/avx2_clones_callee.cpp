// A function that avx2_clones_test.cpp's copies call from another file: LLVM issue 58740's
// shape, where Clang 14's LTO dropped what target_clones' copies call, and the link failed.
namespace glint::test {

[[gnu::noinline]] void addOne(float* values, int n) {
  for (int i = 0; i < n; ++i) values[i] += 1.0f;
}

}  // namespace glint::test
