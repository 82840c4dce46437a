/*
 * check.h - the few helpers the C API tests share: one line per check ("ok: ..." or
 * "FAIL: ..."), a count of failures, and the exit status of the program (0 when every check
 * passed). Each test program in test/c/ covers one behaviour of include/greenconv.h.
 */
#ifndef GREENCONV_TEST_CHECK_H
#define GREENCONV_TEST_CHECK_H

#include <stdio.h>
#include <string.h>

static int check_failures = 0;

/* Print one line for a check and count it when it failed. */
static inline void check(int passed, const char *what, const char *detail)
{
    printf("%s: %s%s%s\n", passed ? "ok" : "FAIL", what, detail && *detail ? " -- " : "",
           detail ? detail : "");
    if (!passed) check_failures++;
}

/* A status and a message: passes when status == expected and message contains `word`. */
static inline void check_status(int status, int expected, const char *message, const char *word, const char *what)
{
    char detail[600];
    snprintf(detail, sizeof detail, "status %d (expected %d), message '%.480s'", status, expected, message);
    check(status == expected && (word == NULL || strstr(message, word) != NULL), what, detail);
}

/* The exit status of a test program. */
static inline int check_exit(void)
{
    return check_failures == 0 ? 0 : 1;
}

#endif
