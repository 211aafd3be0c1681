#!/bin/sh
# plot_remove_dofs.sh: plots the CSV of bench_remove_dofs with gnuplot, one PNG per mesh.
# With PLOT_PREFIX=insert_dofs (what plot_insert_dofs.sh sets) it plots bench_insert_dofs' CSV.
#
# Usage: bench/plot_remove_dofs.sh DIR [DIR...]
#
# For every DIR/remove_dofs_<mesh>.csv (the medians; the _samples and _setup files are skipped) it
# writes DIR/remove_dofs_<mesh>.png with two panels against the seam length l (log-log):
# update + Dirichlet solve time of every method (columns <method>_ms; ours auto thick, ours forced
# routes dashed, the peers solid) and the flop fraction of each update (<method>_flop_fraction).
# Methods are taken from the CSV header, so a build without some route still plots.
# Needs gnuplot 5 (Debian: apt-get install gnuplot-nox). Exit code 1 if gnuplot is missing or a
# folder holds no CSV.

set -eu

prefix="${PLOT_PREFIX:-remove_dofs}"
case "$prefix" in
  insert_dofs) heading="Adding dofs"; ylabel="update + solve [ms] (median)"; name="plot_insert_dofs.sh" ;;
  *) heading="Removing dofs"; ylabel="update + Dirichlet solve [ms] (median)"; name="plot_remove_dofs.sh" ;;
esac

if ! command -v gnuplot >/dev/null 2>&1; then
  echo "$name: gnuplot not found (Debian/Ubuntu: apt-get install gnuplot-nox)" >&2
  exit 1
fi
if [ "$#" -eq 0 ]; then
  echo "usage: $0 DIR [DIR...]   (folders given to bench_${prefix} --csv-dir)" >&2
  exit 1
fi

# The cairo terminal if this gnuplot has it, libgd's png otherwise.
if gnuplot -e "set terminal" 2>&1 | grep -q pngcairo; then
  terminal="pngcairo size 1400,560 font ',10'"
else
  terminal="png size 1400,560"
fi

found=0
for dir in "$@"; do
  for csv in "$dir"/"$prefix"_*.csv; do
    [ -f "$csv" ] || continue
    case "$csv" in *_samples.csv|*_setup.csv) continue ;; esac
    found=1
    png="${csv%.csv}.png"
    if [ "$(wc -l < "$csv")" -lt 2 ]; then
      echo "skipping $csv: no data rows (yet)" >&2
      continue
    fi
    mesh=$(basename "$csv" .csv | sed "s/^${prefix}_//")
    setup="${csv%.csv}_setup.csv"
    vertices=""
    threads=""
    if [ -f "$setup" ]; then
      vertices=$(awk -F, '$2 == "vertices" { printf "%d", $3 }' "$setup")
      threads=$(awk -F, '$2 == "threads" { printf "%d", $3 }' "$setup")
    fi
    methods=$(head -n 1 "$csv" | tr ',' '\n' | grep '_ms$' |
              grep -v -e '_min_ms$' -e '_max_ms$' -e '_call_ms$' -e '^ours_restore_ms$' -e '^ours_merge_ms$' -e '_setup_ms$' -e '_update_ms$' | sed 's/_ms$//')

    time_plot=""
    flop_plot=""
    index=0
    for m in $methods; do
      index=$((index + 1))
      # a fixed, readable colour per position (ours first, then the peers)
      colour=$(echo "#9400d3 #009e73 #56b4e9 #e69f00 #a08000 #0072b2 #d7191c #000000 #808080 #f0027f" |
               cut -d ' ' -f "$(( (index - 1) % 10 + 1 ))")
      case "$m" in
        ours_auto|ours_insert) style="lw 3 dt 1 pt 7 ps 1.2" ;;
        ours_*) style="lw 1.5 dt 2 pt 6" ;;
        *) style="lw 1.5 dt 1 pt 5" ;;
      esac
      title=$(echo "$m" | tr '_' ' ')
      time_plot="${time_plot:+$time_plot, }'$csv' using 1:(column('${m}_ms')) with linespoints $style lc rgb '$colour' title '$title'"
      flop_plot="${flop_plot:+$flop_plot, }'$csv' using 1:(column('${m}_flop_fraction')) with linespoints $style lc rgb '$colour' title '$title'"
    done

    gnuplot <<EOF
set terminal $terminal
set output '$png'
set termoption noenhanced
set datafile separator ','
set datafile missing 'NaN'
set key autotitle columnheader
set logscale xy
set autoscale xfix
set offsets graph 0.03, graph 0.03, 0, 0
set grid
set xlabel 'seam length l [vertices]'
set multiplot layout 1,2 title '$heading: $mesh${vertices:+ ($vertices vertices}${threads:+, $threads thread(s)}${vertices:+)}'
set ylabel '$ylabel'
set key top left
plot $time_plot
set ylabel 'update flops / full factorization flops'
set key bottom right
plot $flop_plot
unset multiplot
EOF
    echo "wrote $png"
  done
done

if [ "$found" -eq 0 ]; then
  echo "$name: no ${prefix}_*.csv in $*" >&2
  exit 1
fi
