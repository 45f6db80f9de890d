# high depends on mid, mid on low; high does not name low.
set(MODULES low mid high)
set(low_DEPS)
set(mid_DEPS low)
set(high_DEPS mid)
