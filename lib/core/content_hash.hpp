#pragma once
// SHA-256 digests (OpenSSL's libcrypto) of text and of files, as lowercase hex: what keys a
// sweep's checkpoint to its inputs and detects a run record edited after it was written.
#include <string>

namespace wr {

std::string sha256_hex(const std::string& bytes);
// MD5, only where a file format prescribes it (the checksums of X3P archives, ISO 25178-72).
std::string md5_hex(const std::string& bytes);
// Streams the file; throws InputError(path, ...) when it cannot be read.
std::string sha256_file_hex(const std::string& path);

}  // namespace wr
