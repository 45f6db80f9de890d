// exr_blocks_agree A.exr B.exr PER_COUNT [BLOCK]: do two independent renders
// of one scene agree within Monte Carlo noise? Compares the totals of the
// irradiance.E and XYZ.Y channels and their sums over BLOCK x BLOCK pixel
// blocks (default 32). With unit-weight beams a pixel's irradiance is
// PER_COUNT (W/m^2 carried by one counted beam) times a Poisson count, so a
// block sum S has variance PER_COUNT * S, and the difference of two
// independent renders PER_COUNT * (S_A + S_B). A counted beam adds at most
// c = 683 lm/W x PER_COUNT x max ybar (1 for the CIE 1931 2-degree observer)
// to Y, so Var(S) <= c E[S] bounds Y's variance the same way (with c for
// PER_COUNT). Agreement: |S_A - S_B| <= 5 sigma for both totals and every
// block.
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
#include <utility>
#include <vector>

namespace {

struct Channel {
  int width = 0, height = 0;
  std::vector<float> values;
};

Channel readChannel(const char* path, const char* name) {
  Imf::InputFile file(path);
  const Imath::Box2i window = file.header().dataWindow();
  Channel c;
  c.width = window.max.x - window.min.x + 1;
  c.height = window.max.y - window.min.y + 1;
  c.values.assign(size_t(c.width) * c.height, 0.0f);
  if (!file.header().channels().findChannel(name))
    throw std::runtime_error(std::string(path) + " has no " + name + " channel");
  Imf::FrameBuffer buffer;
  char* base = reinterpret_cast<char*>(c.values.data() - window.min.x - window.min.y * c.width);
  buffer.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * c.width));
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  return c;
}

// Prints and checks one channel: the total and every block within 5 sigma.
bool blocksAgree(const char* name, const Channel& a, const Channel& b, double unit, int block) {
  auto z = [&](double sa, double sb) {
    const double sigma = std::sqrt(unit * (sa + sb));
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
  std::printf("%s total: %.7g vs %.7g, z = %.2f; %d blocks of %dx%d, worst z = %.2f at (%d, %d)\n", name, totalA, totalB,
              totalZ, blocks, block, block, worst, worstX, worstY);
  // With many blocks some |z| near 4 is expected by chance; 5 sigma per
  // block keeps the false-alarm rate below 1e-6 per block.
  return std::abs(totalZ) <= 5.0 && std::abs(worst) <= 5.0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4 || argc > 5) {
    std::fprintf(stderr, "usage: exr_blocks_agree A.exr B.exr PER_COUNT [BLOCK]\n");
    return 2;
  }
  try {
    const double perCount = std::strtod(argv[3], nullptr);
    const int block = argc == 5 ? std::atoi(argv[4]) : 32;
    if (!(perCount > 0.0) || block < 1) {
      std::fprintf(stderr, "exr_blocks_agree: a bad PER_COUNT or BLOCK\n");
      return 2;
    }
    bool agree = true;
    const std::pair<const char*, double> checks[] = {{"irradiance.E", perCount}, {"XYZ.Y", 683.0 * perCount}};
    for (const auto& [name, unit] : checks) {
      const Channel a = readChannel(argv[1], name), b = readChannel(argv[2], name);
      if (a.width != b.width || a.height != b.height) {
        std::fprintf(stderr, "exr_blocks_agree: different image sizes\n");
        return 2;
      }
      agree &= blocksAgree(name, a, b, unit, block);
    }
    return agree ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exr_blocks_agree: %s\n", e.what());
    return 2;
  }
}
