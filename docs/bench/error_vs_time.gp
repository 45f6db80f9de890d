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
0.000672418 2.45367
0.000906865 0.800998
0.00302993 0.252205
0.0248846 0.0789241
0.250543 0.0249586
2.47012 0.0080504
EOD
$d1_0 << EOD
0.000309279 2.45367
0.00106972 0.800998
0.00782583 0.252205
0.0525173 0.0789241
0.427019 0.0249586
3.92808 0.0080504
EOD
plot $d0_0 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_0 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0080504*(x/2.47012)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'point_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_1 << EOD
0.00140084 3.92447
0.00210504 1.32748
0.00419998 0.424239
0.0333547 0.125531
0.246789 0.0389811
2.33867 0.0125417
EOD
$d1_1 << EOD
0.000443849 3.92447
0.00112141 1.32748
0.00563623 0.424239
0.0377871 0.125531
0.389694 0.0389811
3.57224 0.0125417
EOD
plot $d0_1 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_1 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0125417*(x/2.33867)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_2 << EOD
0.000787298 1.50901
0.000989789 0.473034
0.00349025 0.145537
0.029168 0.0485828
0.305607 0.0153916
3.09878 0.00474422
EOD
$d1_2 << EOD
0.000232605 1.50901
0.00093022 0.473034
0.00600676 0.145537
0.0493349 0.0485828
0.470867 0.0153916
4.76195 0.00474422
EOD
plot $d0_2 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_2 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00474422*(x/3.09878)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_3 << EOD
0.0006336 2.01884
0.00111998 0.618676
0.00628476 0.192406
0.0454292 0.0605442
0.315537 0.0184
2.92327 0.00625028
EOD
$d1_3 << EOD
0.000197934 2.01884
0.00100875 0.618676
0.00589567 0.192406
0.0472251 0.0605442
0.466206 0.0184
4.50125 0.00625028
EOD
plot $d0_3 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_3 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00625028*(x/2.92327)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'furnace' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_4 << EOD
0.000439662 1.95744
0.000581413 0.691132
0.00279772 0.234013
0.0301288 0.0714504
0.231636 0.0203218
2.35505 0.00700781
EOD
$d1_4 << EOD
0.00012858 1.95744
0.000735321 0.691132
0.00479955 0.234013
0.0376347 0.0714504
0.364444 0.0203218
3.62345 0.0070078
EOD
plot $d0_4 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_4 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00700781*(x/2.35505)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_d65' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_5 << EOD
0.000588273 0.663477
0.00109658 0.205715
0.00499449 0.0652183
0.0546878 0.0189764
0.339633 0.00626652
3.17227 0.00201212
EOD
$d1_5 << EOD
0.000122833 0.663477
0.000705977 0.205715
0.00449585 0.0652183
0.0363241 0.0189764
0.349724 0.00626653
3.55243 0.00201212
EOD
plot $d0_5 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_5 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/3.17227)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_a' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_6 << EOD
0.000439221 0.663477
0.000703234 0.205715
0.00340862 0.0652183
0.0314006 0.0189764
0.312419 0.00626653
3.37736 0.00201212
EOD
$d1_6 << EOD
0.000150403 0.663477
0.000684786 0.205715
0.00451254 0.0652183
0.0363542 0.0189764
0.352541 0.00626652
3.58955 0.00201212
EOD
plot $d0_6 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_6 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/3.37736)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f2' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_7 << EOD
0.000344451 0.663477
0.000626149 0.205715
0.00347127 0.0652183
0.0387881 0.0189764
0.343159 0.00626652
4.17672 0.00201212
EOD
$d1_7 << EOD
0.000125997 0.663477
0.000677735 0.205715
0.00449671 0.0652183
0.0371978 0.0189764
0.350911 0.00626653
3.58178 0.00201212
EOD
plot $d0_7 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_7 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/4.17672)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f11' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_8 << EOD
0.000626599 0.663477
0.000965183 0.205715
0.00448111 0.0652183
0.0407352 0.0189764
0.400277 0.00626652
4.15656 0.00201212
EOD
$d1_8 << EOD
0.000117905 0.663477
0.000686459 0.205715
0.00443868 0.0652183
0.0364429 0.0189764
0.35248 0.00626653
3.54317 0.00201212
EOD
plot $d0_8 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_8 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/4.15656)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_led_b3' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_9 << EOD
0.000590917 0.663477
0.00090344 0.205715
0.00650631 0.0652183
0.0416093 0.0189764
0.409528 0.00626652
4.12286 0.00201212
EOD
$d1_9 << EOD
0.000117524 0.663477
0.000685798 0.205715
0.00453106 0.0652183
0.0384005 0.0189764
0.354815 0.00626653
3.66835 0.00201212
EOD
plot $d0_9 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_9 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/4.12286)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'laser_532' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_10 << EOD
0.000882129 0.745339
0.00135691 0.237721
0.00601258 0.0773089
0.0590984 0.0238119
0.497181 0.00742963
3.66411 0.00228176
EOD
$d1_10 << EOD
0.000100239 0.745339
0.000615914 0.237721
0.00442256 0.0773089
0.0385831 0.0238119
0.376497 0.00742963
3.86809 0.00228175
EOD
plot $d0_10 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_10 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00228176*(x/3.66411)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_rect' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_11 << EOD
0.000857482 0.651221
0.00145062 0.191512
0.00496798 0.0673776
0.0426462 0.0199254
0.469418 0.00640466
5.08648 0.00224578
EOD
$d1_11 << EOD
0.000243311 0.651221
0.00103527 0.191512
0.00648881 0.0673777
0.0525866 0.0199254
0.507023 0.00640467
5.27783 0.00224578
EOD
plot $d0_11 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_11 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00224578*(x/5.08648)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_small' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_12 << EOD
0.000773007 0.878509
0.00134471 0.265263
0.0072607 0.0888789
0.0617763 0.0285845
0.684426 0.00867623
5.22966 0.00283295
EOD
$d1_12 << EOD
0.000155681 0.878509
0.000904593 0.265263
0.00596899 0.0888789
0.0491453 0.0285845
0.473323 0.00867623
4.67609 0.00283295
EOD
plot $d0_12 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_12 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00283295*(x/5.22966)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
unset multiplot
