// The source of glarecam_test_pch (tests/CMakeLists.txt): nothing of its own; CMake builds the
// test executables' shared precompiled header with this file's flags.
