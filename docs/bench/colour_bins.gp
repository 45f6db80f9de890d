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
16 0.0017162 9.2267e-05
32 0.000258531 9.2267e-05
64 0.00014376 9.2267e-05
94 0.000113826 9.2267e-05
471 9.26348e-05 9.2267e-05
EOD
$c1 << EOD
16 0.0121752 5.32003e-06
32 0.00262316 5.32003e-06
64 0.00029502 5.32003e-06
94 0.00022691 5.32003e-06
471 1.33908e-05 5.32003e-06
EOD
$c2 << EOD
16 0.00961326 1.36321e-05
32 0.00155785 1.36321e-05
64 0.000361473 1.36321e-05
94 0.000157452 1.36321e-05
471 7.26746e-06 1.36321e-05
EOD
$c3 << EOD
16 0.0670156 1.19956e-08
32 0.0245413 1.19956e-08
64 0.00596781 1.19956e-08
94 0.00487085 1.19956e-08
471 0.00124584 1.19956e-08
EOD
plot $c0 using 1:2 with linespoints lw 2 lc 1 title 'D65, bins', $c0 using 1:3 with linespoints lw 2 dt 2 lc 1 title 'D65, per beam', $c1 using 1:2 with linespoints lw 2 lc 2 title 'F11, bins', $c1 using 1:3 with linespoints lw 2 dt 2 lc 2 title 'F11, per beam', $c2 using 1:2 with linespoints lw 2 lc 3 title 'LED-B3, bins', $c2 using 1:3 with linespoints lw 2 dt 2 lc 3 title 'LED-B3, per beam', $c3 using 1:2 with linespoints lw 2 lc 4 title 'line 532 nm, bins', $c3 using 1:3 with linespoints lw 2 dt 2 lc 4 title 'line 532 nm, per beam', 5e-5 with lines lc 'gray' dt 3 title 'target 5e-5'
