#pragma once
// SHA-256 of input bytes: the scene's text and the files it names are
// fingerprinted with it (a render state records them), and the loaders that
// read those files take it of the bytes they read.
#include <string>
#include <string_view>

namespace spectrace {

// Lowercase hex SHA-256 of `bytes` (OpenSSL EVP). Throws SceneError if
// OpenSSL fails.
std::string sceneSha256Hex(std::string_view bytes);

}  // namespace spectrace
