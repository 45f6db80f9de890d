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
16 0.00175777 0.000135583
32 0.000301238 0.000135583
64 0.000185797 0.000135583
94 0.000156843 0.000135583
471 0.000135837 0.000135583
EOD
$c1 << EOD
16 0.0121981 2.48196e-05
32 0.0026238 2.48196e-05
64 0.000314714 2.48196e-05
94 0.000248013 2.48196e-05
471 3.40785e-05 2.48196e-05
EOD
$c2 << EOD
16 0.00963875 2.16898e-05
32 0.00158267 2.16898e-05
64 0.000384568 2.16898e-05
94 0.000180043 2.16898e-05
471 2.4841e-05 2.16898e-05
EOD
$c3 << EOD
16 0.0670156 1.29136e-08
32 0.0245413 1.29136e-08
64 0.00596781 1.29136e-08
94 0.00487085 1.29136e-08
471 0.00124584 1.29136e-08
EOD
plot $c0 using 1:2 with linespoints lw 2 lc 1 title 'D65, bins', $c0 using 1:3 with linespoints lw 2 dt 2 lc 1 title 'D65, per beam', $c1 using 1:2 with linespoints lw 2 lc 2 title 'F11, bins', $c1 using 1:3 with linespoints lw 2 dt 2 lc 2 title 'F11, per beam', $c2 using 1:2 with linespoints lw 2 lc 3 title 'LED-B3, bins', $c2 using 1:3 with linespoints lw 2 dt 2 lc 3 title 'LED-B3, per beam', $c3 using 1:2 with linespoints lw 2 lc 4 title 'line 532 nm, bins', $c3 using 1:3 with linespoints lw 2 dt 2 lc 4 title 'line 532 nm, per beam', 5e-5 with lines lc 'gray' dt 3 title 'target 5e-5'
