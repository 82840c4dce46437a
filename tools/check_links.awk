# check_links.awk: print "file:line: dead link 'TARGET': why" for each relative Markdown link of
# the files given whose file or heading does not exist (tools/check_links.sh runs it; POSIX awk,
# mawk included).
#
# Checked: inline links and images, [text](target) and ![alt](target), outside fenced code
# blocks (``` or ~~~), indented code blocks and inline code spans. A target with a scheme
# (https:, mailto:, ...) is not ours and is skipped. Any other target is a path relative to the
# file's folder (a leading / means the folder the check runs in, the repository's top), which
# must exist, then an optional #anchor: on a .md file it must be the GitHub anchor of one of
# its headings (lower case; punctuation dropped; blanks made hyphens; a repeated heading gets
# -1, -2, ...). An anchor on any other kind of file is not checked.
# At the end one line "links: N checked in M files, K dead" goes to standard output.

# The folder part of a path, "." when there is none.
function folder_of(path) {
    if (path !~ /\//) return "."
    sub(/\/[^\/]*$/, "", path)
    return path == "" ? "/" : path
}

# A path with "." and "x/.." parts removed.
function normalise(path,    n, parts, out, k, i, result) {
    n = split(path, parts, "/")
    k = 0
    for (i = 1; i <= n; i++) {
        if (parts[i] == "" || parts[i] == ".") continue
        if (parts[i] == ".." && k > 0 && out[k] != "..") { k--; continue }
        out[++k] = parts[i]
    }
    result = ""
    for (i = 1; i <= k; i++) result = result (i > 1 ? "/" : "") out[i]
    if (path ~ /^\//) return "/" result
    return result == "" ? "." : result
}

# GitHub's anchor of a heading's text: inline code marks and link syntax dropped, lower case,
# every character other than a letter, digit, blank, hyphen or underscore dropped, blanks made
# hyphens. Bytes of multibyte UTF-8 letters are kept; the Latin-1 (C2 xx) and general
# punctuation (E2 80 xx) sequences that GitHub drops are dropped too (en and em dashes, middle
# dots).
function slug(text) {
    gsub(/`/, "", text)
    gsub(/!?\[/, "", text)
    gsub(/\]\([^)]*\)/, "", text)
    text = tolower(text)
    gsub(/\302[\200-\277]/, "", text)
    gsub(/\342\200[\200-\277]/, "", text)
    gsub(/[^a-z0-9 _\200-\377-]/, "", text)
    gsub(/ /, "-", text)
    return text
}

# Is this line (of a file being read) a fence line, code, or a heading? Updates the fence state
# kept per file in in_fence[] and previous_blank[].
function classify(file, line) {
    if (line ~ /^[ ]*(```|~~~)/) {
        in_fence[file] = !in_fence[file]
        previous_blank[file] = 0
        return "fence"
    }
    if (in_fence[file]) return "code"
    if (line ~ /^(    |\t)/ && (previous_blank[file] || previous_code[file])) {
        previous_code[file] = 1
        previous_blank[file] = 0
        return "code"
    }
    previous_code[file] = 0
    previous_blank[file] = (line ~ /^[ \t]*$/)
    if (line ~ /^#+[ \t]/) return "heading"
    return "text"
}

# Record the anchors of a Markdown file's headings (once per file); 0 when it cannot be read.
function load_anchors(path,    line, text, kind, base, status) {
    if (path in loaded) return loaded[path]
    in_fence[path] = 0; previous_blank[path] = 1; previous_code[path] = 0
    status = 0
    split("", slug_count)
    while ((getline line < path) > 0) {
        status = 1
        kind = classify(path, line)
        if (kind != "heading") continue
        text = line
        sub(/^#+[ \t]+/, "", text)
        sub(/[ \t]+#+[ \t]*$/, "", text)
        sub(/[ \t]+$/, "", text)
        base = slug(text)
        if (base in slug_count) anchors[path, base "-" slug_count[base]++] = 1
        else { anchors[path, base] = 1; slug_count[base] = 1 }
    }
    close(path)
    loaded[path] = status
    return status
}

function exists(path) {
    return system("test -e '" path "'") == 0
}

function dead(target, why) {
    printf "%s:%d: dead link '%s': %s\n", FILENAME, FNR, target, why
    n_dead++
}

# Check one link target found in the current file.
function check_target(target,    path, anchor, hash, resolved) {
    sub(/^[ \t]*</, "", target)
    sub(/>[ \t]*$/, "", target)
    sub(/[ \t]+("[^"]*"|'[^']*')[ \t]*$/, "", target)
    if (target ~ /^[a-zA-Z][a-zA-Z0-9+.-]*:/) return
    n_links++
    hash = index(target, "#")
    path = hash ? substr(target, 1, hash - 1) : target
    anchor = hash ? substr(target, hash + 1) : ""
    if (path == "") resolved = FILENAME
    else if (path ~ /^\//) resolved = normalise(substr(path, 2))
    else resolved = normalise(folder_of(FILENAME) "/" path)
    if (path != "" && !exists(resolved)) { dead(target, "no file " resolved); return }
    if (anchor == "" || resolved !~ /\.md$/) return
    if (!load_anchors(resolved)) { dead(target, "cannot read " resolved); return }
    if (!((resolved, anchor) in anchors)) dead(target, "no heading with anchor #" anchor " in " resolved)
}

FNR == 1 {
    n_files++
    in_fence[FILENAME "\001"] = 0; previous_blank[FILENAME "\001"] = 1; previous_code[FILENAME "\001"] = 0
}

{
    kind = classify(FILENAME "\001", $0)
    if (kind == "fence" || kind == "code") next
    line = $0
    # inline code spans cannot hold links
    gsub(/`[^`]*`/, "", line)
    while (match(line, /\]\([^)]*\)/)) {
        target = substr(line, RSTART + 2, RLENGTH - 3)
        line = substr(line, RSTART + RLENGTH)
        check_target(target)
    }
}

END {
    printf "links: %d checked in %d files, %d dead\n", n_links, n_files, n_dead
    exit n_dead > 0
}
