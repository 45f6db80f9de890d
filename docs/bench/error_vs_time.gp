set terminal pngcairo size 1600,1520 font 'sans,9'
set output 'docs/bench/error_vs_time.png'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key bottom left
set multiplot layout 4,4 title 'relative RMSE of pixel irradiance against wall time (trace + resolve)'
set title 'point_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_0 << EOD
0.0012291 2.45367
0.00126899 0.800998
0.00332823 0.252205
0.0232489 0.0789241
0.22141 0.0249586
2.15545 0.0080504
EOD
$d1_0 << EOD
0.000257552 2.45367
0.00104086 0.800998
0.00734741 0.252205
0.0405824 0.0789241
0.353837 0.0249586
4.14736 0.0080504
EOD
plot $d0_0 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_0 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0080504*(x/2.15545)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'point_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_1 << EOD
0.00102914 3.92447
0.00134677 1.32748
0.00413772 0.424239
0.0241429 0.125531
0.20273 0.0389811
2.00669 0.0125417
EOD
$d1_1 << EOD
0.000496467 3.92447
0.00112349 1.32748
0.00595494 0.424239
0.0467539 0.125531
0.444984 0.0389811
4.33288 0.0125417
EOD
plot $d0_1 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_1 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0125417*(x/2.00669)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_2 << EOD
0.000785856 1.50901
0.00101523 0.473034
0.00289563 0.145537
0.0208907 0.0485828
0.17263 0.0153916
1.83256 0.00474422
EOD
$d1_2 << EOD
0.000342978 1.50901
0.00167959 0.473034
0.00767829 0.145537
0.0642294 0.0485828
0.671403 0.0153916
6.15798 0.00474422
EOD
plot $d0_2 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_2 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00474422*(x/1.83256)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_3 << EOD
0.000572139 2.01884
0.000656645 0.618676
0.00242982 0.192406
0.0198993 0.0605442
0.202864 0.0184
1.70655 0.00625028
EOD
$d1_3 << EOD
0.000230532 2.01884
0.000924142 0.618676
0.00688694 0.192406
0.0814774 0.0605442
0.548666 0.0184
4.94478 0.00625028
EOD
plot $d0_3 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_3 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00625028*(x/1.70655)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'furnace' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_4 << EOD
0.000387034 1.95744
0.000696153 0.691132
0.00170685 0.234013
0.0137175 0.0714504
0.132866 0.0203218
1.41492 0.00700781
EOD
$d1_4 << EOD
0.000142241 1.95744
0.000780839 0.691132
0.0048489 0.234013
0.0401012 0.0714504
0.422973 0.0203218
4.40992 0.0070078
EOD
plot $d0_4 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_4 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00700781*(x/1.41492)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_d65' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_5 << EOD
0.0021099 0.663477
0.00215971 0.205715
0.00446888 0.0652183
0.0236461 0.0189764
0.211498 0.00626652
1.99393 0.00201212
EOD
$d1_5 << EOD
0.000131085 0.663477
0.000710594 0.205715
0.00540695 0.0652183
0.0451482 0.0189764
0.443674 0.00626653
5.0144 0.00201212
EOD
plot $d0_5 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_5 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/1.99393)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_a' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_6 << EOD
0.00171919 0.663477
0.00196937 0.205715
0.00423174 0.0652183
0.0273001 0.0189764
0.261603 0.00626653
2.34123 0.00201212
EOD
$d1_6 << EOD
0.000120338 0.663477
0.000702903 0.205715
0.00520027 0.0652183
0.0504086 0.0189764
0.440406 0.00626652
4.47237 0.00201212
EOD
plot $d0_6 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_6 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/2.34123)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f2' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_7 << EOD
0.0026274 0.663477
0.00276917 0.205715
0.00478737 0.0652183
0.0241689 0.0189764
0.216761 0.00626652
1.98999 0.00201212
EOD
$d1_7 << EOD
0.000124534 0.663477
0.000684195 0.205715
0.00494459 0.0652183
0.0437539 0.0189764
0.436591 0.00626653
4.51191 0.00201212
EOD
plot $d0_7 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_7 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/1.98999)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f11' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_8 << EOD
0.00247854 0.663477
0.00279378 0.205715
0.00460631 0.0652183
0.0241325 0.0189764
0.217612 0.00626652
2.6173 0.00201212
EOD
$d1_8 << EOD
0.000117734 0.663477
0.000665278 0.205715
0.00495137 0.0652183
0.0428828 0.0189764
0.420916 0.00626653
4.31414 0.00201212
EOD
plot $d0_8 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_8 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/2.6173)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_led_b3' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_9 << EOD
0.00169067 0.663477
0.00185126 0.205715
0.00426234 0.0652183
0.0255605 0.0189764
0.219264 0.00626652
1.9555 0.00201212
EOD
$d1_9 << EOD
0.000197293 0.663477
0.00105437 0.205715
0.00677618 0.0652183
0.0504673 0.0189764
0.488588 0.00626653
3.93792 0.00201212
EOD
plot $d0_9 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_9 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/1.9555)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'laser_532' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_10 << EOD
0.000535485 0.745339
0.000788771 0.237721
0.00247139 0.0773089
0.0204142 0.0238119
0.190096 0.00742963
1.72589 0.00228176
EOD
$d1_10 << EOD
9.8796e-05 0.745339
0.000637867 0.237721
0.00444476 0.0773089
0.0392762 0.0238119
0.379683 0.00742963
3.90599 0.00228175
EOD
plot $d0_10 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_10 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00228176*(x/1.72589)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_rect' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_11 << EOD
0.00256102 0.651221
0.00277675 0.191512
0.00678106 0.0673776
0.0369711 0.0199254
0.339213 0.00640466
2.93259 0.00224578
EOD
$d1_11 << EOD
0.000259636 0.651221
0.00103693 0.191512
0.00661783 0.0673777
0.0740525 0.0199254
0.760164 0.00640467
5.75936 0.00224578
EOD
plot $d0_11 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_11 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00224578*(x/2.93259)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_small' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_12 << EOD
0.00276726 0.878509
0.00343625 0.265263
0.00950026 0.0888789
0.0378421 0.0285845
0.435147 0.00867623
4.51988 0.00283295
EOD
$d1_12 << EOD
0.000372913 0.878509
0.00144317 0.265263
0.00610043 0.0888789
0.0608274 0.0285845
0.553224 0.00867623
5.19323 0.00283295
EOD
plot $d0_12 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_12 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00283295*(x/4.51988)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
unset multiplot
