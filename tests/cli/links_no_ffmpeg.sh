#!/usr/bin/env bash
# Fails when the program given loads any of FFmpeg's libraries at start-up (ldd: its whole dependency tree).
#
# Usage: tests/cli/links_no_ffmpeg.sh PROGRAM      (ctest: Webm.VotsDoesNotLinkFfmpeg)
set -euo pipefail

libs="$(ldd "$1")"
grep -q 'libc\.so' <<<"$libs" || { echo "links_no_ffmpeg: FAIL: ldd $1 lists no libc:" >&2; echo "$libs" >&2; exit 1; }
if grep -E 'lib(avformat|avcodec|avutil|swscale|swresample)\.so' <<<"$libs"; then
    echo "links_no_ffmpeg: FAIL: $1 loads FFmpeg at start-up (above)" >&2
    exit 1
fi
echo "links_no_ffmpeg: PASS: $(wc -l <<<"$libs") libraries, none of FFmpeg's"
