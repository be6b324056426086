# Included by ctest after the discovered GoogleTest tests (tests/CMakeLists.txt,
# TEST_INCLUDE_FILES). gtest_discover_tests' PROPERTIES cannot carry a list value in CMake 3.25:
# ENVIRONMENT "OMP_NUM_THREADS=1;OMP_WAIT_POLICY=passive" arrived as OMP_NUM_THREADS=1 alone
# (the second item became a stray argument) and LABELS "verification;slow" would be cut the same
# way. The list values are therefore set here, on the lists the discovery leaves (TEST_LIST).
foreach(test IN LISTS rigidflex_unit_tests_TESTS rigidflex_verification_fast_tests
                      rigidflex_verification_slow_tests)
  set_tests_properties("${test}" PROPERTIES ENVIRONMENT "OMP_NUM_THREADS=1;OMP_WAIT_POLICY=passive")
endforeach()
# "slow": left out of the sanitizer run (CMakePresets.json, test preset "sanitize").
foreach(test IN LISTS rigidflex_verification_slow_tests)
  set_tests_properties("${test}" PROPERTIES LABELS "verification;slow")
endforeach()
