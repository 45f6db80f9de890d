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
0.000637746 2.48151
0.000822921 0.814132
0.00200506 0.250412
0.0144217 0.0737579
0.138083 0.0242166
1.35666 0.00768919
EOD
$d1_0 << EOD
0.000196582 2.48151
0.000618508 0.814132
0.00499 0.250412
0.0286959 0.0737579
0.255335 0.0242166
2.52108 0.00768918
EOD
plot $d0_0 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_0 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00768919*(x/1.35666)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'point_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_1 << EOD
0.000631908 3.13913
0.000719047 1.24226
0.00183307 0.386499
0.0135962 0.127715
0.131136 0.039639
1.30812 0.0126134
EOD
$d1_1 << EOD
0.000251853 3.13913
0.000665718 1.24226
0.00335597 0.386499
0.0257191 0.127715
0.243822 0.039639
2.44396 0.0126134
EOD
plot $d0_1 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_1 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.0126134*(x/1.30812)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_2 << EOD
0.00220798 1.43653
0.000846156 0.481258
0.00223285 0.160017
0.0173895 0.0486866
0.165889 0.0149436
1.67347 0.00500333
EOD
$d1_2 << EOD
0.000225915 1.43653
0.00086919 0.481258
0.00514869 0.160017
0.0403534 0.0486866
0.386605 0.0149436
3.88616 0.00500333
EOD
plot $d0_2 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_2 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00500333*(x/1.67347)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_3 << EOD
0.000517388 2.09389
0.000690084 0.610668
0.00217418 0.184784
0.0168383 0.0576963
0.171819 0.0187082
1.77899 0.00605956
EOD
$d1_3 << EOD
0.000193267 2.09389
0.000813477 0.610668
0.00487087 0.184784
0.0385997 0.0576963
0.369828 0.0187082
3.70124 0.00605956
EOD
plot $d0_3 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_3 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00605956*(x/1.77899)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'furnace' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_4 << EOD
0.000293055 2.15149
0.000455837 0.705714
0.00161833 0.223067
0.0134364 0.0688873
0.130393 0.0237385
1.29997 0.0066814
EOD
$d1_4 << EOD
0.000120669 2.15149
0.000631287 0.705714
0.00401785 0.223067
0.0317468 0.0688873
0.304389 0.0237385
3.0481 0.0066814
EOD
plot $d0_4 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_4 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.0066814*(x/1.29997)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_d65' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_5 << EOD
0.00161339 0.594722
0.00166809 0.203314
0.0031182 0.0611355
0.0184037 0.0189767
0.169927 0.00615257
1.69826 0.00196103
EOD
$d1_5 << EOD
0.000116392 0.594722
0.000636685 0.203314
0.00413277 0.0611355
0.0345516 0.0189767
0.339497 0.00615257
3.23343 0.00196104
EOD
plot $d0_5 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_5 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/1.69826)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_a' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_6 << EOD
0.00183189 0.594722
0.0019644 0.203314
0.00446646 0.0611355
0.0187315 0.0189767
0.169172 0.00615257
1.68055 0.00196103
EOD
$d1_6 << EOD
0.000117504 0.594722
0.000630786 0.203314
0.00410657 0.0611355
0.0332511 0.0189767
0.318915 0.00615257
3.18767 0.00196104
EOD
plot $d0_6 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_6 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/1.68055)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f2' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_7 << EOD
0.00165719 0.594722
0.00162952 0.203314
0.0030905 0.0611355
0.0184475 0.0189767
0.170551 0.00615257
1.69098 0.00196103
EOD
$d1_7 << EOD
0.000113789 0.594722
0.000623084 0.203314
0.00404534 0.0611355
0.0334475 0.0189767
0.337147 0.00615257
3.52925 0.00196103
EOD
plot $d0_7 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_7 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/1.69098)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f11' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_8 << EOD
0.00170838 0.594722
0.00176445 0.203314
0.00310654 0.0611355
0.0183089 0.0189767
0.170734 0.00615257
1.69245 0.00196103
EOD
$d1_8 << EOD
0.000143373 0.594722
0.000688061 0.203314
0.00525161 0.0611355
0.0402846 0.0189767
0.396931 0.00615257
3.2858 0.00196103
EOD
plot $d0_8 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_8 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/1.69245)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_led_b3' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_9 << EOD
0.00167356 0.594722
0.00169921 0.203314
0.00408754 0.0611355
0.0189288 0.0189767
0.179556 0.00615257
1.72115 0.00196103
EOD
$d1_9 << EOD
0.000124385 0.594722
0.000626439 0.203314
0.00411359 0.0611355
0.0334472 0.0189767
0.323276 0.00615257
3.30579 0.00196103
EOD
plot $d0_9 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_9 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/1.72115)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'laser_532' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_10 << EOD
0.000467414 0.73791
0.000591718 0.23595
0.00183482 0.0767803
0.0152603 0.023128
0.151329 0.00729035
1.52807 0.00237266
EOD
$d1_10 << EOD
0.000123343 0.73791
0.000584047 0.23595
0.00412344 0.0767803
0.0355437 0.023128
0.346937 0.00729035
3.47528 0.00237266
EOD
plot $d0_10 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_10 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00237266*(x/1.52807)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_rect' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_11 << EOD
0.00191808 0.661868
0.00204371 0.230997
0.00452567 0.0636716
0.027075 0.020916
0.251575 0.00644784
2.497 0.00203705
EOD
$d1_11 << EOD
0.000215981 0.661868
0.000906976 0.230997
0.00557053 0.0636716
0.0446434 0.020916
0.443559 0.00644784
4.29405 0.00203705
EOD
plot $d0_11 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_11 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00203705*(x/2.497)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_small' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_12 << EOD
0.00194104 0.831923
0.00218164 0.268993
0.00449289 0.0822313
0.0300775 0.025986
0.250949 0.00857101
2.47037 0.00284146
EOD
$d1_12 << EOD
0.000151114 0.831923
0.000818975 0.268993
0.00527821 0.0822313
0.0421669 0.025986
0.406294 0.00857101
4.06234 0.00284147
EOD
plot $d0_12 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_12 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00284146*(x/2.47037)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
unset multiplot
