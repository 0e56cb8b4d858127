# Every dependency is a Debian package found by find_package; nothing is downloaded or vendored.
# scripts/setup.sh installs the packages (the list lives there and in docs/building.md).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(Ceres 2.0 REQUIRED)
find_package(SUNDIALS 6 REQUIRED COMPONENTS cvodes nvecserial)
find_package(NLopt 2.7 REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(fmt 9 REQUIRED)
find_package(CLI11 2.1 REQUIRED)
find_package(Threads REQUIRED)
# k-d tree of the irreducible-error estimate (libnanoflann-dev, header only).
find_package(nanoflann 1.3 REQUIRED)
# MAT (libmatio-dev) and HDF5 (libhdf5-dev, the serial build) recordings, through pkg-config.
find_package(PkgConfig REQUIRED)
pkg_check_modules(SYSID_MATIO REQUIRED IMPORTED_TARGET GLOBAL matio)
pkg_check_modules(SYSID_HDF5 REQUIRED IMPORTED_TARGET GLOBAL hdf5-serial)
# zlib (zlib1g-dev): the MAT v5 layout check inflates compressed variables itself.
find_package(ZLIB REQUIRED)
# libcrypto (libssl-dev): the SHA-256 of a model file in an export's provenance.
find_package(OpenSSL 3 REQUIRED COMPONENTS Crypto)
# Boost.Math headers (libboost-dev): the signal tests cross-check Savitzky-Golay against
# boost::math::differentiation::discrete_lanczos_derivative. Tests only: not a library dependency.
if(SYSID_BUILD_TESTS)
  find_package(Boost 1.71 REQUIRED)
endif()
