# A two-module graph in which high depends on low, never the reverse.
set(MODULES low high)
set(low_DEPS)
set(high_DEPS low)
