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
16 4.94723e-05 4.94723e-05
32 5.41816e-05 5.41816e-05
64 5.04597e-05 5.04597e-05
94 5.79281e-05 5.79281e-05
471 5.23702e-05 5.23702e-05
EOD
$c1 << EOD
16 7.75501e-05 7.75501e-05
32 7.37828e-05 7.37828e-05
64 7.76417e-05 7.76417e-05
94 7.3708e-05 7.3708e-05
471 7.55033e-05 7.55033e-05
EOD
$c2 << EOD
16 3.54227e-05 3.54227e-05
32 2.97689e-05 2.97689e-05
64 3.24183e-05 3.24183e-05
94 3.92001e-05 3.92001e-05
471 3.76696e-05 3.76696e-05
EOD
$c3 << EOD
16 1e-09 1e-09
32 1e-09 1e-09
64 1e-09 1e-09
94 1e-09 1e-09
471 1e-09 1e-09
EOD
plot $c0 using 1:2 with linespoints lw 2 lc 1 title 'D65, bins', $c0 using 1:3 with linespoints lw 2 dt 2 lc 1 title 'D65, per beam', $c1 using 1:2 with linespoints lw 2 lc 2 title 'F11, bins', $c1 using 1:3 with linespoints lw 2 dt 2 lc 2 title 'F11, per beam', $c2 using 1:2 with linespoints lw 2 lc 3 title 'LED-B3, bins', $c2 using 1:3 with linespoints lw 2 dt 2 lc 3 title 'LED-B3, per beam', $c3 using 1:2 with linespoints lw 2 lc 4 title 'line 532 nm, bins', $c3 using 1:3 with linespoints lw 2 dt 2 lc 4 title 'line 532 nm, per beam', 5e-5 with lines lc 'gray' dt 3 title 'target 5e-5'
