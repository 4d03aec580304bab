# ctest includes this after the discovered tests of granjet_stability_tests, whose names the
# discovery leaves in granjet_stability_tests_TESTS: label them `stability` and `long`. (A list
# given to gtest_discover_tests' PROPERTIES loses its separator on the way to the discovery
# script, so two labels cannot be set there.)
foreach(test IN LISTS granjet_stability_tests_TESTS)
  set_tests_properties("${test}" PROPERTIES LABELS "stability;long")
endforeach()
