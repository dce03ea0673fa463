# One clamping scenario's run as a figure (docs/sil.md#report): command,
# response and limits against time, stacked panels sharing the time axis.
#   gnuplot -e "csv='OUT/sil-tip-in.csv'; png='OUT/sil-tip-in.png'; name='tip-in'; slip_limit=0.10" \
#     hil/sil/sil_clamp_plot.gp
# Columns: cvtplant-sil's trace (docs/sil.md#scenarios).
if (!exists("csv")) csv = "sil-tip-in.csv"
if (!exists("png")) png = "sil-tip-in.png"
if (!exists("name")) name = "tip-in"
if (!exists("how")) how = "lock-step, 10 ms control period, 1 ms plant frames"
if (!exists("slip_limit")) slip_limit = 0.10
set terminal pngcairo size 1100,1000 font ",10" noenhanced
set output png
set datafile separator ","
set grid
set key outside right top
set lmargin 12
set rmargin 30
set multiplot layout 4,1 title "cvtplant SIL: ".name.", example controller (".how.")"
set format x ""
set ylabel "torque [N m]"
plot csv using 1:2 skip 1 with steps lw 1.5 title "driver demand (command)", \
     csv using 1:5 skip 1 with lines lw 1.5 title "transmitted (response)"
set ylabel "clamping force [kN]"
set yrange [0:*]
plot csv using 1:($3/1000) skip 1 with steps title "clamp command", \
     csv using 1:($4/1000) skip 1 with lines title "driver axial force"
set ylabel "slip [-]"
set yrange [-1.5*slip_limit:1.5*slip_limit]
plot csv using 1:6 skip 1 with lines title "slip", \
     slip_limit with lines dt 2 lc "red" title sprintf("limit +/-%g", slip_limit), \
     -slip_limit with lines dt 2 lc "red" notitle
set format x "%g"
set xlabel "time [s]"
set ylabel "safety factor [-]"
set yrange [0:5]
plot csv using 1:9 skip 1 with lines title "torque capacity / |torque|", \
     1.05 with lines dt 2 lc "red" title "gross-slip limit 1.05", \
     csv using 1:($10 + 2*$11) skip 1 with steps lc "black" title "fault (1 timeout, 2 watchdog)"
unset multiplot
