# Shared by the plot scripts that read a contact run's column file, which a run writes as text,
# <name>_<method>.dat, or with `&scene output_format = 'binary'` as <name>_<method>.bin (rows of
# little-endian float64) beside the text header <name>_<method>.bin.txt. Both carry the same
# '#' header lines, the last naming the columns. A script loads this file, then
#
#   file = column_file(sprintf('%s/%s_%s', datadir, scene, method))
#   opts = data_options(file)        # '' for text, "binary format='%5float64'" for binary
#   plot file @opts using (column_of(file, 't')):(column_of(file, 'u'))
#
# column_file(base): base.'.dat' or base.'.bin' (with its .bin.txt), whichever exists; the newer
#     one when both do (the last run's); '' when neither. Set `format = 'text'` or 'binary'
#     beforehand (gnuplot -e "format='binary'") to take only that one.
# header_of(file): the file that holds its '#' lines: file itself, or file.'.txt' for a .bin.
# column_names(file): the last '#' line of its header (the column names, '#' first).
# n_columns(file), column_of(file, name): the number of columns, the number of a named column
#     (0 when absent).
# data_options(file): what goes between the file name and `using` in a plot or stats command
#     (a string variable expanded as a macro, @opts): '' for text, the binary record format
#     with the column count of its header for binary.
# missing_file(base): the message for a run whose column file is absent.

if (!exists("format")) format = ''

is_binary(file) = strlen(file) > 4 && file[strlen(file) - 3:] eq '.bin'
header_of(file) = is_binary(file) ? file.'.txt' : file
readable(file) = system(sprintf("test -r '%s' && echo 1 || echo 0", file)) eq '1'
column_file(base) = system(sprintf( \
    "t='%s.dat'; b='%s.bin'; want='%s'; " . \
    "has_t=0; has_b=0; " . \
    "[ \"$want\" != binary ] && [ -r \"$t\" ] && has_t=1; " . \
    "[ \"$want\" != text ] && [ -r \"$b\" ] && [ -r \"$b.txt\" ] && has_b=1; " . \
    "if [ $has_t = 1 ] && [ $has_b = 1 ]; then if [ \"$b\" -nt \"$t\" ]; then echo \"$b\"; else echo \"$t\"; fi; " . \
    "elif [ $has_b = 1 ]; then echo \"$b\"; elif [ $has_t = 1 ]; then echo \"$t\"; fi", base, base, format))
column_names(file) = system(sprintf("grep '^#' '%s' | tail -n 1", header_of(file)))
n_columns(file) = words(column_names(file)) - 1
column_of(file, name) = sum [i = 2:words(column_names(file))] (word(column_names(file), i) eq name ? i - 1 : 0)
data_options(file) = is_binary(file) ? sprintf("binary format='%%%dfloat64'", n_columns(file)) : ''
missing_file(base) = sprintf("cannot read %s.dat or %s.bin (run the scene first: make run)", base, base)
