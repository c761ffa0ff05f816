#pragma once
// Typed exceptions shared by libgeodesic and libgeotri. The libraries never print or exit: they throw one of these,
// and the tools turn it into a one-line message and an exit code.

#include <stdexcept>
#include <string>

namespace geotri {

/// Base of every exception that geotri throws on purpose.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The caller handed over something unusable: bad indices, NaN coordinates, an unknown surface point.
class InvalidInput : public Error {
public:
    using Error::Error;
};

/// The mesh's connectivity breaks a precondition: non-manifold, open, inconsistently oriented.
class TopologyError : public Error {
public:
    using Error::Error;
};

/// A file could not be read or written, or its content is malformed.
class IOError : public Error {
public:
    using Error::Error;
};

/// A computation met a numerical situation that it cannot resolve exactly.
class NumericalError : public Error {
public:
    using Error::Error;
};

}  // namespace geotri
