set terminal pngcairo size 1000,600 font 'sans,10'
set output 'docs/bench/colour_bins.png'
set logscale xy
set grid
set key outside right
set xlabel 'wavelength bins (360-830 nm)'
set ylabel 'chromaticity error |Δ(x,y)| of the image mean'
set xtics (16,32,64,94,471)
set title 'colour from bin-averaged CMFs (solid) vs per-beam CMFs (dashed)'
$c0 << EOD
16 2.11047e-05 2.11047e-05
32 1.66625e-05 1.66625e-05
64 1.53106e-05 1.53106e-05
94 6.49922e-06 6.49922e-06
471 1.02664e-05 1.02664e-05
EOD
$c1 << EOD
16 2.9369e-05 2.9369e-05
32 3.23749e-05 3.23749e-05
64 3.58262e-05 3.58262e-05
94 3.49873e-05 3.49873e-05
471 3.49409e-05 3.49409e-05
EOD
$c2 << EOD
16 2.717e-05 2.717e-05
32 3.38499e-05 3.38499e-05
64 3.58044e-05 3.58044e-05
94 3.93738e-05 3.93738e-05
471 3.82857e-05 3.82857e-05
EOD
$c3 << EOD
16 1e-09 1e-09
32 1e-09 1e-09
64 1e-09 1e-09
94 1e-09 1e-09
471 1e-09 1e-09
EOD
plot $c0 using 1:2 with linespoints lw 2 lc 1 title 'D65, bins', $c0 using 1:3 with linespoints lw 2 dt 2 lc 1 title 'D65, per beam', $c1 using 1:2 with linespoints lw 2 lc 2 title 'F11, bins', $c1 using 1:3 with linespoints lw 2 dt 2 lc 2 title 'F11, per beam', $c2 using 1:2 with linespoints lw 2 lc 3 title 'LED-B3, bins', $c2 using 1:3 with linespoints lw 2 dt 2 lc 3 title 'LED-B3, per beam', $c3 using 1:2 with linespoints lw 2 lc 4 title 'line 532 nm, bins', $c3 using 1:3 with linespoints lw 2 dt 2 lc 4 title 'line 532 nm, per beam', 5e-5 with lines lc 'gray' dt 3 title 'target 5e-5'
