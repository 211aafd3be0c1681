#!/bin/sh
# plot_insert_dofs.sh: plots the CSV of bench_insert_dofs with gnuplot, one PNG per mesh
# (DIR/insert_dofs_<mesh>.png: update + solve time and flop fraction of every method against the
# seam length l, log-log; ours insert thick, ours remove dashed, the peers solid).
#
# Usage: bench/plot_insert_dofs.sh DIR [DIR...]   (folders given to bench_insert_dofs --csv-dir)
# The plotting itself is plot_remove_dofs.sh's, for the insert_dofs_*.csv files. Needs gnuplot 5.
PLOT_PREFIX=insert_dofs exec sh "$(dirname "$0")/plot_remove_dofs.sh" "$@"
