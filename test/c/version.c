/*
 * The version: gc_version reports the library's "major.minor.patch" (fpm.toml's version),
 * equal to the header's GREENCONV_VERSION, and writes it as every message of the C API is
 * written: a short buffer gets what fits and a NUL with status 2, a NULL buffer status 2,
 * nothing past the buffer.
 */
#include <string.h>
#include "greenconv.h"
#include "check.h"

int main(void)
{
    char text[64], detail[200];
    size_t length;
    int status;

    memset(text, '#', sizeof text);
    status = gc_version(text, sizeof text);
    snprintf(detail, sizeof detail, "library \"%.40s\", header \"%s\", status %d", text, GREENCONV_VERSION, status);
    check(status == GC_OK && strcmp(text, GREENCONV_VERSION) == 0,
          "gc_version equals the header's GREENCONV_VERSION", detail);

    length = strlen(GREENCONV_VERSION);
    memset(text, '#', sizeof text);
    status = gc_version(text, length + 1);
    check(status == GC_OK && strcmp(text, GREENCONV_VERSION) == 0 && text[length + 1] == '#',
          "a buffer of exactly length + 1 bytes: the whole version, nothing past it", text);

    memset(text, '#', sizeof text);
    status = gc_version(text, 3);
    check(status == GC_ERROR_INPUT && strlen(text) == 2 && strncmp(text, GREENCONV_VERSION, 2) == 0
              && text[3] == '#',
          "a 3-byte buffer: status 2, the first 2 bytes and a NUL, nothing past the buffer", text);

    memset(text, '#', sizeof text);
    status = gc_version(text, 0);
    check(status == GC_ERROR_INPUT && text[0] == '#', "text_len = 0: status 2, nothing written", NULL);

    status = gc_version(NULL, 16);
    check(status == GC_ERROR_INPUT, "text NULL: status 2, no crash", NULL);

    return check_exit();
}
