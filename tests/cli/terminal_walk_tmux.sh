#!/usr/bin/env bash
# The interactive walk of `facet step` on a real terminal: tmux runs it in a detached 80×30 window, the
# test types keys with send-keys and reads the window with capture-pane after each: forward, back, to
# another pixel (the stage is kept), then q, and the program must exit with status 0.
# Run by ctest as Terminal.StepWalkThroughTmux: terminal_walk_tmux.sh FACET SOURCE_DIR.
# Exits 77 (ctest's skip) when tmux is not installed.
set -euo pipefail
facet=$1
root=$2
if ! command -v tmux > /dev/null; then
    echo "skipped: the test needs tmux (Debian package tmux)"
    exit 77
fi

model=models/cube/cube.obj
first_pixel=400,300
second_pixel=420,280
work=$(mktemp -d)
# A tmux server of the test's own (-L), so that it never sees or touches the user's sessions.
tmux=(tmux -u -L "facet-step-walk-$$" -f /dev/null)
cleanup() {
    "${tmux[@]}" kill-server 2> /dev/null || true
    rm -rf "$work"
}
trap cleanup EXIT

# The stage titles, as the walk shows them, from the same command without a terminal (--print), which
# writes each stage as "K. TITLE" between two rules of 80 '='.
(cd "$root" && "$facet" step "$model" --pixel "$first_pixel" --print) > "$work/print.txt"
rule=$(printf '=%.0s' $(seq 80))
awk -v rule="$rule" 'prev2 == rule && $0 == rule { print prev1 } { prev2 = prev1; prev1 = $0 }' \
    "$work/print.txt" > "$work/titles.txt"
stages=$(wc -l < "$work/titles.txt")
if [ "$stages" -lt 3 ]; then
    echo "facet step --print showed $stages stages; the test needs at least 3:"
    cat "$work/print.txt"
    exit 1
fi
# title_of K: the start of stage K's title: up to 40 characters, ending before the first that is not
# plain ASCII, so that it matches whatever the locale makes of the rest.
title_of() {
    sed -n "s/^$1\. //p" "$work/titles.txt" | LC_ALL=C sed 's/[^ -~].*//' | cut -c1-40
}

"${tmux[@]}" new-session -d -s walk -x 80 -y 30 \
    "cd '$root' && '$facet' step '$model' --pixel '$first_pixel'; echo \$? > '$work/status'; sleep 600"

screen() { "${tmux[@]}" capture-pane -p -t walk; }
# wait_for TEXT WHAT: waits until the window shows TEXT (a fixed string), or fails after 60 s.
wait_for() {
    for _ in $(seq 600); do
        # The window captured first, then searched: grep -q stopping early must not fail the capture.
        if grep -q -F -- "$1" <<< "$(screen)"; then return 0; fi
        sleep 0.1
    done
    echo "after $2 the window does not show \"$1\"; it shows:"
    screen
    exit 1
}
keys() { "${tmux[@]}" send-keys -t walk "$@"; }

wait_for "Stage 1 of $stages: $(title_of 1)" "starting"
wait_for "Pixel (${first_pixel/,/, })" "starting"

keys Enter
wait_for "Stage 2 of $stages: $(title_of 2)" "Enter (the next stage)"
keys n Enter
wait_for "Stage 3 of $stages: $(title_of 3)" "n (the next stage)"
keys b Enter
wait_for "Stage 2 of $stages: $(title_of 2)" "b (back a stage)"

keys "p $second_pixel" Enter
wait_for "Pixel (${second_pixel/,/, })" "p $second_pixel (another pixel)"
wait_for "Stage 2 of " "p $second_pixel (the same stage)"

keys q Enter
for _ in $(seq 600); do
    [ -s "$work/status" ] && break
    sleep 0.1
done
if [ ! -s "$work/status" ]; then
    echo "facet step did not end after q; the window shows:"
    screen
    exit 1
fi
status=$(cat "$work/status")
if [ "$status" != 0 ]; then
    echo "facet step ended with status $status after q"
    screen
    exit 1
fi
echo "the walk went forward, back and to another pixel in tmux, and q ended it with status 0"
