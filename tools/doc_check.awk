# doc_check.awk: print "file:line: what" for each public entity of free-form Fortran sources
# without a FORD `!>` comment on the line right above it (`make doc-check`).
#
# Checked: every `module NAME`; in a module, every name listed in a `public ::` statement (or
# declared with the public attribute) that this file defines as a type, a procedure, a
# generic interface or a named constant or variable; the components of such a type, and
# the type-bound procedures of a type that extends no other (an extension's bindings that
# override documented deferred ones inherit their documentation); the dummy arguments (lines
# with `intent(`) of such a procedure. Private helpers and interface bodies are not checked.

function trim(x) {
    sub(/^[ \t]+/, "", x)
    sub(/[ \t]+$/, "", x)
    return x
}

function report(line, what) {
    printf "%s:%d: %s without a !> comment\n", FILENAME, line, what
}

# Names of a comma-separated list, without initialisations or array bounds.
function add_public(list,    n, i, parts, name) {
    n = split(list, parts, ",")
    for (i = 1; i <= n; i++) {
        name = trim(parts[i])
        sub(/[ \t]*=.*/, "", name)
        if (name != "" && name !~ /^(operator|assignment)/) public[name] = 1
    }
}

FNR == 1 {
    split("", public)
    split("", pending_names)
    n_pending = 0
    in_type = 0; in_interface = 0; in_proc = ""; continuing = 0; after_contains = 0
    previous_doc = 0
}

{
    line = tolower($0)
    is_doc = (line ~ /^[ \t]*!>/)
    code = line
    sub(/!.*/, "", code)
    code = trim(code)
}

# Blank and comment lines: a `!>` line documents what follows.
code == "" { previous_doc = is_doc ? 1 : (trim(line) == "" ? 0 : previous_doc); next }

continuing {
    add_public(code)
    continuing = (code ~ /&$/)
    sub(/&$/, "", code)
    previous_doc = 0
    next
}

code ~ /^contains$/ && !in_type { after_contains = 1 }

code ~ /^(abstract[ \t]+)?interface([ \t]|$)/ {
    name = code
    sub(/^(abstract[ \t]+)?interface[ \t]*/, "", name)
    if (name != "" && (name in public) && !previous_doc) report(FNR, "generic interface " name)
    in_interface++
    previous_doc = 0
    next
}
code ~ /^end[ \t]*interface/ { in_interface--; previous_doc = 0; next }
in_interface > 0 { previous_doc = 0; next }

code ~ /^module[ \t]+[a-z][a-z0-9_]*$/ {
    if (!previous_doc) report(FNR, "module " $2)
    previous_doc = 0
    next
}

code ~ /^public[ \t]*::/ {
    list = code
    sub(/^public[ \t]*::/, "", list)
    continuing = (list ~ /&$/)
    sub(/&$/, "", list)
    add_public(list)
    previous_doc = 0
    next
}

# A derived type.
!after_contains && (code ~ /^type[ \t]*,.*::/ || code ~ /^type[ \t]*::/ || code ~ /^type[ \t]+[a-z][a-z0-9_]*$/) {
    name = code
    if (name ~ /::/) sub(/^.*::[ \t]*/, "", name)
    else sub(/^type[ \t]+/, "", name)
    name = trim(name)
    if (code ~ /,[ \t]*public/) public[name] = 1
    type_name = name
    type_checked = (name in public)
    type_extends = (code ~ /extends[ \t]*\(/)
    type_bindings = 0
    if (type_checked && !previous_doc) report(FNR, "type " name)
    in_type = 1
    previous_doc = 0
    next
}
in_type && code ~ /^end[ \t]*type/ { in_type = 0; previous_doc = 0; next }
in_type && code ~ /^contains$/ { type_bindings = 1; previous_doc = 0; next }
in_type {
    if (type_checked && code !~ /^(private|sequence|final|generic)/ && !previous_doc) {
        if (!type_bindings) report(FNR, "component of " type_name)
        else if (!type_extends) report(FNR, "type-bound procedure of " type_name)
    }
    previous_doc = 0
    next
}

# A named constant or variable in the specification part.
!after_contains && code ~ /::/ && code !~ /^(use|import|private|public|procedure)/ {
    list = code
    sub(/^.*::/, "", list)
    n = split(list, parts, ",")
    for (i = 1; i <= n; i++) {
        name = trim(parts[i])
        sub(/[ \t]*[=(].*/, "", name)
        if (code ~ /,[ \t]*public/) public[name] = 1
        if ((name in public) && !previous_doc) report(FNR, name)
    }
    previous_doc = 0
    next
}

# A module procedure.
after_contains && in_proc == "" && code ~ /^((pure|elemental|impure|recursive|module|non_recursive)[ \t]+)*((real|integer|logical|complex|character|type|class)[^ ]*[ \t]+)*(subroutine|function)[ \t]+[a-z]/ {
    name = code
    sub(/\(.*/, "", name)
    n = split(name, words, /[ \t]+/)
    name = words[n]
    if (name in public) {
        in_proc = name
        if (!previous_doc) report(FNR, "procedure " name)
    } else {
        in_proc = "-"
        private_proc = name
    }
    previous_doc = 0
    next
}
in_proc != "" && code ~ /^end[ \t]*(subroutine|function)/ { in_proc = ""; previous_doc = 0; next }
in_proc != "" && in_proc != "-" && code ~ /intent[ \t]*\(/ {
    if (!previous_doc) report(FNR, "argument of " in_proc)
}

{ previous_doc = 0 }
