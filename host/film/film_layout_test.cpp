// The film's channel list against the device layout, and pack/unpack
// through it for every channel set.
#include "film/film_layout.h"

#include <gtest/gtest.h>

#include <vector>

namespace spectrace {
namespace {

FilmLayout smallFilm(bool exactColour, uint32_t weightUnits) {
  FilmLayout film;
  film.pixelsX = 5;
  film.pixelsY = 4;
  film.bins = 9;
  film.window = {1, 1, 3, 2};
  film.firstStoredBin = 2;
  film.storedBins = 5;
  film.exactColour = exactColour;
  film.weightUnits = weightUnits;
  return film;
}

// A histogram with a distinct value in every counter the film stores.
SpectralHistogram distinctStoredCounts(const FilmLayout& film) {
  SpectralHistogram h = film.emptyHistogram();
  uint64_t next = 1;
  for (const StoredChannel& ch : film.channels())
    for (uint64_t p = 0; p < film.pixelCount(); ++p)
      if (film.storesPixel(p))
        for (uint32_t i = ch.hostFirst; i < ch.hostFirst + ch.counters; ++i)
          h.channel(ch.channel)[p * ch.hostCounters + i] = next++;
  return h;
}

TEST(FilmLayout, ChannelsTileAPixelsCountersInChannelOrder) {
  for (bool colour : {false, true})
    for (uint32_t units : {1u, 1024u}) {
      const FilmLayout film = smallFilm(colour, units);
      uint32_t offset = 0, previous = 0;
      for (const StoredChannel& ch : film.channels()) {
        EXPECT_EQ(ch.deviceOffset, offset);
        EXPECT_TRUE(offset == 0 || ch.channel > previous);
        offset += ch.counters;
        previous = ch.channel;
      }
      EXPECT_EQ(offset, film.countersPerPixel()) << "colour " << colour << ", units " << units;
      EXPECT_EQ(film.channels().size(), 1u + colour + (units != 1));
    }
}

TEST(FilmLayout, PackThenUnpackGivesBackEveryChannel) {
  for (bool colour : {false, true})
    for (uint32_t units : {1u, 1024u}) {
      const FilmLayout film = smallFilm(colour, units);
      const SpectralHistogram h = distinctStoredCounts(film);
      std::vector<uint64_t> counters(film.storedCounterCount());
      packDeviceCounters(h, film, 0, counters);
      SpectralHistogram back = film.emptyHistogram();
      unpackDeviceCounters(counters, film, 0, back);
      for (uint32_t c = 0; c < device::kFilmChannelCount; ++c)
        EXPECT_EQ(back.channel(c), h.channel(c)) << filmChannelName(c) << ", colour " << colour << ", units " << units;
    }
}

TEST(FilmLayout, PackRefusesCountsTheDeviceDoesNotStore) {
  const FilmLayout film = smallFilm(true, 1024);
  std::vector<uint64_t> counters(film.storedCounterCount());
  SpectralHistogram outsideWindow = film.emptyHistogram();
  outsideWindow.colourSums()[0] = 1;  // pixel 0 is outside the window
  EXPECT_THROW(packDeviceCounters(outsideWindow, film, 0, counters), std::invalid_argument);
  SpectralHistogram outsideBins = film.emptyHistogram();
  outsideBins.at(uint32_t(film.fullPixelOfStored(0)), 0) = 1;  // bin 0 is below the stored bins
  EXPECT_THROW(packDeviceCounters(outsideBins, film, 0, counters), std::invalid_argument);
}

}  // namespace
}  // namespace spectrace
