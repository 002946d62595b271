# cmake/npm_package.cmake against a registry folder made here (file:// URLs)
# from tests/npm_package/fake-1.0.0.tgz: a scoped package is fetched,
# checked and extracted (its executable still runs), a second call fetches
# nothing, and a file that is not the locked one, a missing file, an entry
# that is not in the lock and an integrity that is not sha512 each give
# their reason and leave nothing behind.
#   cmake -DTARBALL=tests/npm_package/fake-1.0.0.tgz -DWORK=.. -P npm_package_test.cmake
cmake_minimum_required(VERSION 3.19)
include(${CMAKE_CURRENT_LIST_DIR}/../cmake/npm_package.cmake)

function(expect what actual expected)
  if(NOT "${actual}" STREQUAL "${expected}")
    message(FATAL_ERROR "${what}: got '${actual}', expected '${expected}'")
  endif()
endfunction()
function(expect_match what actual pattern)
  if(NOT "${actual}" MATCHES "${pattern}")
    message(FATAL_ERROR "${what}: got '${actual}', expected it to match '${pattern}'")
  endif()
endfunction()

# The base64 of the lock file's integrity, as hex: SHA-512("abc") (FIPS 180-2).
_ccma_base64_to_hex("3a81oZNherrMQXNJriBBMRLm+k6JqX6iCp7u5ktV05ohkpkqJ0/BqDa6PCOj/uu9RU1EI2Q86A4qmslPpUyknw==" hex)
expect("base64 of SHA-512(abc)" "${hex}"
       "ddaf35a193617abacc417349ae20413112e6fa4e89a97ea20a9eeee64b55d39a2192992a274fc1a836ba3c23a3feebbd454d4423643ce80e2a9ac94fa54ca49f")
_ccma_base64_to_hex("TWFu" hex)
expect("base64 'TWFu'" "${hex}" "4d616e")
_ccma_base64_to_hex("TWE=" hex)
expect("base64 'TWE='" "${hex}" "4d61")
_ccma_base64_to_hex("TW*u" hex)
expect("base64 with a stray character" "${hex}" "")

file(REMOVE_RECURSE "${WORK}")
set(registry "${WORK}/registry")
configure_file("${TARBALL}" "${registry}/@ccma-test/fake/-/fake-1.0.0.tgz" COPYONLY)
configure_file("${TARBALL}" "${registry}/tampered/-/tampered-1.0.0.tgz" COPYONLY)
set(fake_sha512 "sha512-HsIAFy9omxYs7YbmNvUqxIUDA5EoU6donbyUzislx6IlBSN3oFxXAhDFnUdusqb/5zWIijqHfvAGJAU5JN8/aQ==")
set(abc_sha512 "sha512-3a81oZNherrMQXNJriBBMRLm+k6JqX6iCp7u5ktV05ohkpkqJ0/BqDa6PCOj/uu9RU1EI2Q86A4qmslPpUyknw==")
set(lock "${WORK}/package-lock.json")
file(WRITE "${lock}" "{\"lockfileVersion\": 3, \"packages\": {
  \"node_modules/@ccma-test/fake\": {\"version\": \"1.0.0\", \"integrity\": \"${fake_sha512}\"},
  \"node_modules/tampered\": {\"version\": \"1.0.0\", \"integrity\": \"${abc_sha512}\"},
  \"node_modules/absent\": {\"version\": \"1.0.0\", \"integrity\": \"${fake_sha512}\"},
  \"node_modules/sha1only\": {\"version\": \"1.0.0\", \"integrity\": \"sha1-qZk+NkcGgWq6PiVxeFDCbJzQ2J0=\"}}}\n")
set(CCMA_NPM_REGISTRY "file://${registry}")
set(dest "${WORK}/build")

ccma_npm_package(@ccma-test/fake "${lock}" "${dest}" reason)
expect("a locked scoped package" "${reason}" "")
file(READ "${dest}/node_modules/@ccma-test/fake/package.json" manifest)
expect_match("its package.json" "${manifest}" "\"name\":\"@ccma-test/fake\"")
execute_process(COMMAND "${dest}/node_modules/@ccma-test/fake/bin/tool" OUTPUT_VARIABLE out RESULT_VARIABLE rc)
expect("its executable, run" "${rc}:${out}" "0:fake\n")
if(NOT EXISTS "${dest}/@ccma-test+fake-1.0.0.tgz")
  message(FATAL_ERROR "the tarball is not kept in ${dest}")
endif()

# Fetched once: with the registry gone, the kept copy is used.
file(REMOVE_RECURSE "${registry}/@ccma-test")
ccma_npm_package(@ccma-test/fake "${lock}" "${dest}" reason)
expect("the second call, registry gone" "${reason}" "")
# ... and a damaged extraction is redone from the kept tarball, not fetched.
file(REMOVE "${dest}/node_modules/@ccma-test/fake/.ccma-sha512")
ccma_npm_package(@ccma-test/fake "${lock}" "${dest}" reason)
expect("re-extracted from the kept tarball" "${reason}" "")

ccma_npm_package(tampered "${lock}" "${dest}" reason)
expect_match("a file that is not the locked one" "${reason}"
             "tampered-1.0.0.tgz is not the file the lock file pins \\(sha512 1ec20017.*expected ddaf35a1")
ccma_npm_package(absent "${lock}" "${dest}" reason)
expect_match("a file the registry does not have" "${reason}" "^could not download file://.*/absent/-/absent-1.0.0.tgz: ")
ccma_npm_package(nothere "${lock}" "${dest}" reason)
expect_match("a package the lock does not pin" "${reason}" "pins no version and integrity of nothere$")
ccma_npm_package(sha1only "${lock}" "${dest}" reason)
expect_match("a sha1 integrity" "${reason}" "the integrity of sha1only is not a sha512 hash$")
file(GLOB left RELATIVE "${dest}" "${dest}/*" "${dest}/node_modules/*")
list(SORT left)
expect("what is left" "${left}" "@ccma-test+fake-1.0.0.tgz;node_modules;node_modules/@ccma-test")
message(STATUS "npm_package: all checks passed")
