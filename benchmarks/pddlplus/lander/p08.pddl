(define (problem lander-08)
  (:domain lander)
  (:init
    (flying)
    (= (h) 3019.9) (= (v) -60)
    (= (mass) 1140.64) (= (fuel) 140.64) (= (burn-rate) 5)
    (= (gravity) 3.71) (= (thrust) 9309.9)
    (= (touch-height) 0.8) (= (safe-speed) 1))
  (:goal (and (landed))))
