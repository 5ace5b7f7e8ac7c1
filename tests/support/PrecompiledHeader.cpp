// The translation unit bl_test_pch compiles its precompiled header with (tests/CMakeLists.txt);
// the test executables reuse that header. The program itself (GoogleTest's main) runs no test.
