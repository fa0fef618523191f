#pragma once
// CRC-32 (IEEE 802.3: reflected polynomial 0xEDB88320, initial value and final XOR 0xFFFFFFFF),
// the checksum of zlib and PNG; checkpoints carry it so that damage which still parses as JSON is
// caught. Check value: crc32("123456789") == 0xCBF43926.
#include <cstdint>
#include <string_view>

namespace bhm::evo {

std::uint32_t crc32(std::string_view bytes);

}  // namespace bhm::evo
