#!/bin/sh
# Runs a command on a "full disk": no file may grow past 0 bytes
# (RLIMIT_FSIZE), and SIGXFSZ is ignored, so writes fail with EFBIG as they
# would with ENOSPC. Needs no root, mounts or free space.
trap '' XFSZ
ulimit -f 0
exec "$@"
