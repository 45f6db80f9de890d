// exr_blocks_agree A.exr B.exr PER_COUNT [BLOCK]: do two independent renders
// of one scene agree within Monte Carlo noise? Compares the total of the
// irradiance.E channel and its sums over BLOCK x BLOCK pixel blocks
// (default 32). With unit-weight beams a pixel's irradiance is PER_COUNT
// (W/m^2 carried by one counted beam) times a Poisson count, so a block sum S
// has variance PER_COUNT * S; the difference of two independent renders has
// variance PER_COUNT * (S_A + S_B). Agreement: |S_A - S_B| <= 5 sigma for the
// total and for every block.
//
// Exit status: 0 agree; 1 some block or the total differs by more than
// 5 sigma (the worst is printed); 2 usage or read error.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Channel {
  int width = 0, height = 0;
  std::vector<float> values;
};

Channel readIrradiance(const char* path) {
  Imf::InputFile file(path);
  const Imath::Box2i window = file.header().dataWindow();
  Channel c;
  c.width = window.max.x - window.min.x + 1;
  c.height = window.max.y - window.min.y + 1;
  c.values.assign(size_t(c.width) * c.height, 0.0f);
  if (!file.header().channels().findChannel("irradiance.E"))
    throw std::runtime_error(std::string(path) + " has no irradiance.E channel");
  Imf::FrameBuffer buffer;
  char* base = reinterpret_cast<char*>(c.values.data() - window.min.x - window.min.y * c.width);
  buffer.insert("irradiance.E", Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * c.width));
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4 || argc > 5) {
    std::fprintf(stderr, "usage: exr_blocks_agree A.exr B.exr PER_COUNT [BLOCK]\n");
    return 2;
  }
  try {
    const Channel a = readIrradiance(argv[1]), b = readIrradiance(argv[2]);
    const double perCount = std::strtod(argv[3], nullptr);
    const int block = argc == 5 ? std::atoi(argv[4]) : 32;
    if (a.width != b.width || a.height != b.height || !(perCount > 0.0) || block < 1) {
      std::fprintf(stderr, "exr_blocks_agree: different image sizes, or a bad PER_COUNT or BLOCK\n");
      return 2;
    }
    auto z = [&](double sa, double sb) {
      const double sigma = std::sqrt(perCount * (sa + sb));
      return sigma > 0.0 ? (sa - sb) / sigma : (sa == sb ? 0.0 : INFINITY);
    };
    double totalA = 0.0, totalB = 0.0, worst = 0.0;
    int worstX = -1, worstY = -1, blocks = 0;
    for (int by = 0; by < a.height; by += block)
      for (int bx = 0; bx < a.width; bx += block) {
        double sa = 0.0, sb = 0.0;
        for (int y = by; y < std::min(by + block, a.height); ++y)
          for (int x = bx; x < std::min(bx + block, a.width); ++x) {
            sa += a.values[size_t(y) * a.width + x];
            sb += b.values[size_t(y) * a.width + x];
          }
        totalA += sa;
        totalB += sb;
        ++blocks;
        if (std::abs(z(sa, sb)) > std::abs(worst)) {
          worst = z(sa, sb);
          worstX = bx;
          worstY = by;
        }
      }
    const double totalZ = z(totalA, totalB);
    std::printf("total: %.6g vs %.6g W/m^2 summed, z = %.2f; %d blocks of %dx%d, worst z = %.2f at (%d, %d)\n", totalA,
                totalB, totalZ, blocks, block, block, worst, worstX, worstY);
    // With many blocks some |z| near 4 is expected by chance; 5 sigma per
    // block keeps the false-alarm rate below 1e-6 per block.
    return std::abs(totalZ) <= 5.0 && std::abs(worst) <= 5.0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exr_blocks_agree: %s\n", e.what());
    return 2;
  }
}
