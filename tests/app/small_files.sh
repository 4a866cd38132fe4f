#!/bin/sh
# Runs a command as on a nearly full disk: no file it writes may grow past one block (512 bytes
# or 1 KiB); a write past it fails with EFBIG, as one would with ENOSPC, instead of killing it.
trap '' XFSZ
ulimit -f 1
exec "$@"
