#!/bin/sh
# Writes a man page for an lfcam program from its own help (help2man): the program's --help, and
# for `lfcam` every command's `lfcam help COMMAND` as sections of their own, so `man lfcam` holds
# what `lfcam help` says. Usage: make-manpage.sh PROGRAM NAME-LINE OUT.1.gz [EMULATOR]
# EMULATOR runs a cross-built PROGRAM here (qemu-aarch64-static for the Pis' lfcam-node).
set -eu
program=$1 name=$2 out=$3 emulator=${4:-}
include=$(mktemp)
wrapped=$(mktemp -d)
trap 'rm -rf "$include" "$out.tmp" "$wrapped"' EXIT
if [ -n "$emulator" ]; then
  # help2man runs a path: a script of the program's own name that runs it under the emulator.
  printf '#!/bin/sh\nexec %s %s "$@"\n' "$emulator" "$(realpath "$program")" \
    > "$wrapped/$(basename "$program")"
  chmod +x "$wrapped/$(basename "$program")"
  program="$wrapped/$(basename "$program")"
fi
if [ "$(basename "$program")" = lfcam ]; then
  # The commands, as `lfcam help` lists them ("  NAME   what it does").
  for command in $("$program" help | awk '/^Subcommands:/ {on = 1; next} on && /^  [a-z]/ {print $1}'); do
    [ "$command" = help ] && continue
    printf '[COMMAND: %s]\n' "$command" >> "$include"
    "$program" help "$command" | sed 's/^\./\\\&./' >> "$include"
    printf '\n' >> "$include"
  done
fi
extra=""
[ -s "$include" ] && extra="--include=$include"
# shellcheck disable=SC2086
help2man --no-info --no-discard-stderr --name="$name" $extra \
  --version-string="$("$program" --version | awk '{print $2}')" "$program" > "$out.tmp"
gzip -9n < "$out.tmp" > "$out"
