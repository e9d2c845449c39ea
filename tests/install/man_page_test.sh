#!/bin/bash
# Docs.ManPageCoversEveryOption: the hand-written man page (docs/facet.1) cannot go stale silently. It
# names every command facet --help lists and every long option each command's --help lists, no option
# that none of them lists, and the version facet --version prints; groff formats it without a warning.
# Usage: man_page_test.sh FACET docs/facet.1
set -euo pipefail
facet=$1 page=$2
if ! command -v groff >/dev/null; then
    echo "skipped: no groff (apt-get install groff-base)"
    exit 77
fi
fail=0

warnings=$(groff -man -Tascii -ww -z "$page" 2>&1)
if [ -n "$warnings" ]; then
    echo "groff warns about $page:"
    echo "$warnings"
    fail=1
fi
# The page as a reader sees it, in ASCII (\- is a plain hyphen), without bold and underlining, nor
# hyphenation or line breaks that would cut an option in two.
text=$(groff -man -Tascii -P-cbou -rHY=0 -rLL=300n "$page" 2>/dev/null)

version=$("$facet" --version | head -n 1 | sed 's/^facet //')
grep -q "^\.TH FACET 1 .*\"Facet $version\"" "$page" || {
    echo "$page's .TH line does not carry version $version: $(grep '^\.TH' "$page")"
    fail=1
}

# Commands: the names under "Subcommands:" in facet --help, each with a "facet COMMAND" section.
commands=$("$facet" --help | awk '/^Subcommands:/ { on = 1; next } on && NF { print $1 }')
[ -n "$commands" ] || {
    echo "facet --help lists no commands"
    exit 1
}
listed=" --help --version "
for command in $commands; do
    grep -q "^\.SS facet $command\$" "$page" || {
        echo "$page has no section \".SS facet $command\""
        fail=1
    }
    for option in $("$facet" "$command" --help | grep -oE -- '--[a-z0-9][a-z0-9-]*' | sort -u); do
        listed+="$option "
        grep -qE -- "(^|[^a-z0-9-])$option([^a-z0-9-]|\$)" <<<"$text" || {
            echo "$page does not mention facet $command $option"
            fail=1
        }
    done
done
# And the other way: every option the page names is one some command takes.
# shellcheck disable=SC2013  # options are words
for option in $(grep -oE -- '--[a-z][a-z0-9-]*' <<<"$text" | sort -u); do
    [[ "$listed" == *" $option "* ]] || {
        echo "$page names $option, which no command's --help lists"
        fail=1
    }
done
[ "$fail" = 0 ] && echo "$page covers $(wc -w <<<"$commands") commands and $(tr " " "\n" <<<"$listed" | sort -u | grep -c .) distinct options"
exit "$fail"
