#!/bin/sh
# Bad input must end the run with a non-zero exit status and a message matching REGEX (naming the
# option and value) -- never a crash (signal), a hang (ctest TIMEOUT), a sanitizer's report or a
# silent success.
#   expect_error.sh REGEX command [args...]
regex=$1
shift
out=$("$@" 2>&1)
rc=$?
if [ "$rc" -eq 0 ]; then
  printf 'FAIL: expected an error, the command succeeded:\n%s\n' "$out"
  exit 1
fi
if printf '%s' "$out" | grep -qE 'Segmentation|Caught signal|core dumped|SIGSEGV|SIGFPE'; then
  printf 'FAIL: crashed instead of reporting an error:\n%s\n' "$out"
  exit 1
fi
# sanitized builds (-DTURGOR_SANITIZE=ON): a memory error, a leak or undefined behaviour on the way
# to the error also ends the run non-zero, after the expected message
if printf '%s' "$out" | grep -qE 'ERROR: (Address|Leak)Sanitizer|runtime error: '; then
  printf 'FAIL: a sanitizer reported an error:\n%s\n' "$out"
  exit 1
fi
if ! printf '%s' "$out" | grep -qE -- "$regex"; then
  printf 'FAIL: the error message does not match /%s/:\n%s\n' "$regex" "$out"
  exit 1
fi
printf 'ok (exit %s): %s\n' "$rc" "$(printf '%s' "$out" | grep -E -- "$regex" | head -n 1)"
