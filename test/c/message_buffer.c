/*
 * The message buffer: a length of 0 writes nothing, 1 writes the NUL alone, a short length
 * keeps the first errmsg_len - 1 bytes and a NUL and writes nothing past the buffer, NULL is
 * allowed, a long buffer gets the whole message (longer than 1024 bytes here), and success
 * leaves "".
 */
#include <string.h>
#include "greenconv.h"
#include "check.h"

/* A failing call whose message names a path of `length` characters. */
static int fail_with_path(size_t length, char *buffer, size_t buffer_len)
{
    static char path[4096];
    gc_convolver *conv = NULL;
    memset(path, 'x', length);
    memcpy(path, "missing/", 8);
    path[length] = '\0';
    return gc_convolver_new_frf_file(path, 1e-3, "modal", 10, 1e-6, 30, &conv, buffer, buffer_len);
}

int main(void)
{
    char buffer[4096], full[4096], what[200];
    gc_convolver *conv = NULL;
    size_t length;
    int status;

    status = fail_with_path(2000, full, sizeof full);
    length = strlen(full);
    snprintf(what, sizeof what, "a 2000-character path: the whole message (%zu bytes, more than 1024)", length);
    check(status == GC_ERROR_INPUT && length > 2000, what, NULL);

    memset(buffer, '#', sizeof buffer);
    status = fail_with_path(2000, buffer, 0);
    check(status == GC_ERROR_INPUT && buffer[0] == '#', "errmsg_len = 0: status 2, nothing written", NULL);

    memset(buffer, '#', sizeof buffer);
    status = fail_with_path(2000, buffer, 1);
    check(status == GC_ERROR_INPUT && buffer[0] == '\0' && buffer[1] == '#', "errmsg_len = 1: the NUL alone",
          NULL);

    memset(buffer, '#', sizeof buffer);
    status = fail_with_path(2000, buffer, 8);
    check(status == GC_ERROR_INPUT && strlen(buffer) == 7 && strncmp(buffer, full, 7) == 0 && buffer[8] == '#',
          "errmsg_len = 8: the first 7 bytes, a NUL, nothing past the buffer", buffer);

    memset(buffer, '#', sizeof buffer);
    status = fail_with_path(2000, buffer, length + 1);
    check(status == GC_ERROR_INPUT && strcmp(buffer, full) == 0 && buffer[length + 1] == '#',
          "errmsg_len = length + 1: the whole message exactly", NULL);

    memset(buffer, '#', sizeof buffer);
    status = fail_with_path(2000, buffer, length);
    check(status == GC_ERROR_INPUT && strlen(buffer) == length - 1, "errmsg_len = length: one byte cut", NULL);

    status = fail_with_path(100, NULL, 100);
    check(status == GC_ERROR_INPUT, "errmsg NULL: status 2, no crash", NULL);

    memset(buffer, '#', sizeof buffer);
    status = gc_convolver_new_sdof(1.0, 1e4, 0.1, 1e-3, "exact", 10, &conv, buffer, sizeof buffer);
    check(status == GC_OK && buffer[0] == '\0', "success: the message is \"\"", NULL);
    memset(buffer, '#', sizeof buffer);
    status = gc_convolver_describe(conv, buffer, 6);
    check(status == GC_OK && strcmp(buffer, "exact") == 0, "describe into 6 bytes: \"exact\"", buffer);
    gc_convolver_free(conv);
    return check_exit();
}
